/* climbsim's lockstep participant protocol (docs/design.md#the-shared-simulation-clock,
 * idl/clock.idl) on Cyclone DDS's C API: the same steps as the C++ LockstepParticipant
 * (common/src/lockstep_participant.cpp) and the Python climbsim.lockstep, in plain C for a
 * controller written in C.
 *
 *   cl_participant p;
 *   cl_init(&p, name, domain, period, offset, start_timeout_s);      // DDS entities
 *   cl_input(&p, CLIMBSIM_TOPIC_CHAMBER_STATE, &climbsim_ChamberState_desc, ...);
 *   cl_output(&p, CLIMBSIM_TOPIC_VALVE_COMMAND, &climbsim_ValveCommand_desc);
 *   int code = cl_run(&p, step_fn, user);                            // until the clock's Stop
 *   cl_fini(&p);
 *
 * QoS as deploy/qos/climbsim.xml (docs/controllers.md#topics-and-qos), with XCDR1 forced: Fast DDS
 * 2.9 speaks XCDR1.
 */
#ifndef CLIMBSIM_LOCKSTEP_H
#define CLIMBSIM_LOCKSTEP_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "climbsim_topics.h" /* CLIMBSIM_TOPIC_*: generated from topic_catalog.hpp at build time */
#include "dds/dds.h"

#define CL_EXIT_OK 0     /* run completed or stopped on request */
#define CL_EXIT_FAILED 1 /* the run failed */
#define CL_EXIT_CONFIG 2 /* bad option or roster */

#define CL_MAX_PORTS 8
#define CL_HELD 96 /* samples kept per input (all producers together): more than the window */
#define CL_MAX_NAME 64
#define CL_EARLY_STOPS 16 /* Stops kept from before RunStart */
#define CL_PER_WRITER 34  /* arrivals kept per writer of an input: the step-data history depth */

/* Which QoS profile of deploy/qos/climbsim.xml. */
typedef enum { CL_CONTROL, CL_LATCHED, CL_STEP_DATA, CL_OBSERVER } cl_profile;

/* A step granted to this participant: t_ns = step * dt_ns. */
typedef struct {
  uint64_t step;
  int64_t t_ns;
  int64_t dt_ns;
} cl_step;

/* A sample taken from an input's reader as it arrived, with its writer. */
typedef struct {
  void* sample;
  dds_instance_handle_t writer;
} cl_arrival;

/* A stamped input: samples whose first members are `char source[65]; uint64_t step;
 * int64_t t_ns;` (every climbsim data type). The reader's listener takes every sample as it
 * arrives into `arrivals` (arrival order, at most CL_PER_WRITER per writer: in the reader's
 * shared KEEP_LAST history a writer flooding a key would push another writer's samples out
 * before they are read); samples of the roster's producers are then kept in `held`. */
typedef struct {
  const char* topic;
  const dds_topic_descriptor_t* desc;
  size_t size; /* sizeof the sample type */
  dds_entity_t reader;
  void* held[CL_HELD];
  size_t count;
  pthread_mutex_t lock; /* guards arrivals: the listener runs on a thread of Cyclone's */
  cl_arrival* arrivals;
  size_t n_arrivals, cap_arrivals;
  dds_entity_t wake; /* the participant's guard condition: set when something arrived */
} cl_input_port;

typedef struct {
  const char* topic;
  dds_entity_t writer;
} cl_output_port;

typedef struct cl_participant {
  char name[CL_MAX_NAME + 1];
  uint32_t period_steps, offset_steps;
  double start_timeout_s;
  dds_entity_t domain, participant, waitset;
  dds_entity_t data_guard; /* set by the input readers' listeners, attached to the waitset */
  dds_entity_t grant_reader, run_start_reader, stop_reader, done_writer, ready_writer;
  cl_input_port inputs[CL_MAX_PORTS];
  size_t n_inputs;
  cl_output_port outputs[CL_MAX_PORTS];
  size_t n_outputs;
  void* run_start; /* climbsim_RunStart*, once received */
  /* The clock is the DDS participant (GUID prefix) that sent our RunStart; the
   * launcher's run id (CLIMBSIM_RUN_ID) if given. Samples of anyone else are dropped. */
  uint8_t clock_id[12];
  bool has_expected_run_id;
  uint64_t expected_run_id;
  uint64_t dropped;                   /* samples dropped because of their sender */
  dds_instance_handle_t logged[32];   /* writers whose first dropped sample was logged */
  size_t n_logged;
  void* stop;      /* climbsim_Stop*, once received */
  /* Stops that came before RunStart, with their sender: judged once RunStart binds the clock,
   * or, if the clock leaves without one, the first of the launcher's run id ends the run. The
   * run id is no secret once the clock published RunStart (an outsider reads it there and may
   * forge a Stop that reaches us before our copy of the RunStart). */
  void* early_stops[CL_EARLY_STOPS];
  uint8_t early_senders[CL_EARLY_STOPS][12];
  bool early_sender_known[CL_EARLY_STOPS];
  dds_instance_handle_t early_writers[CL_EARLY_STOPS];
  size_t n_early;
  bool clock_seen; /* a StepGrant writer was matched */
  uint64_t current_step;
  bool in_step;
} cl_participant;

/* Creates the domain (Cyclone configured for the Fast DDS services: loopback, unicast
 * discovery, 4 s lease), the participant and the clock endpoints. Returns 0 or prints why. */
int cl_init(cl_participant* p, const char* name, int domain_id, uint32_t period_steps, uint32_t offset_steps,
            double start_timeout_s);
void cl_fini(cl_participant* p);

/* The QoS of a profile for a reader (writer = false) or a writer. Free with dds_delete_qos. */
dds_qos_t* cl_qos(cl_profile profile, bool writer);

/* Declares a stamped input / output (before cl_run). Return the port index or -1. */
int cl_input(cl_participant* p, const char* topic, const dds_topic_descriptor_t* desc, size_t size);
int cl_output(cl_participant* p, const char* topic, const dds_topic_descriptor_t* desc);

/* Inside a step: sets *sample to what the `producer_index`-th producer of the input (ordered by
 * name; cl_producer_count says how many) wrote at its last due step before s->step, waiting for
 * it, or to NULL if that producer has not been due yet. Returns 0, or -1 if the run ended or the
 * sample is missing (the step must then return non-zero). The sample stays valid in the step. */
size_t cl_producer_count(const cl_participant* p, int input);
int cl_get(cl_participant* p, int input, size_t producer_index, const cl_step* s, const void** sample);

/* Inside a step: sets source, step and t_ns of `sample` and writes it. */
int cl_write(cl_participant* p, int output, void* sample, const cl_step* s);

/* A step function returns 0, or non-zero after putting a message in `why` (fails the run). */
typedef int (*cl_step_fn)(cl_participant* p, const cl_step* s, void* user, char* why, size_t why_size);

/* Announces ready, waits for the run start, arms, calls `fn` at every due step until the clock
 * stops the run. Returns CL_EXIT_*. */
int cl_run(cl_participant* p, cl_step_fn fn, void* user);

#endif
