/* The lockstep participant protocol in C; see climbsim_lockstep.h. */
#include "climbsim_lockstep.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "climbsim_idl_hashes.h"
#include "clock.h"

#define FAILURE_LINGER_NS DDS_SECS(2)

/* The first members of every stamped climbsim data type. */
typedef struct {
  char source[65];
  uint64_t step;
  int64_t t_ns;
} stamp_head;

static dds_time_t now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (dds_time_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static void copy_name(char* dst, size_t size, const char* src) {
  snprintf(dst, size, "%s", src);
}

dds_qos_t* cl_qos(cl_profile profile, bool writer) {
  dds_qos_t* q = dds_create_qos();
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(q, 1, &xcdr1);
  switch (profile) {
    case CL_CONTROL: /* StepGrant, StepDone, ClockControl */
      dds_qset_history(q, DDS_HISTORY_KEEP_LAST, 16);
      dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_durability(q, DDS_DURABILITY_VOLATILE);
      if (writer) dds_qset_liveliness(q, DDS_LIVELINESS_AUTOMATIC, DDS_SECS(1));
      break;
    case CL_LATCHED: /* ParticipantReady, RunStart, Stop */
      dds_qset_history(q, DDS_HISTORY_KEEP_LAST, 1);
      dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_durability(q, DDS_DURABILITY_TRANSIENT_LOCAL);
      if (writer) dds_qset_liveliness(q, DDS_LIVELINESS_AUTOMATIC, DDS_SECS(1));
      break;
    case CL_STEP_DATA: /* stamped data read inside the lockstep */
      dds_qset_history(q, DDS_HISTORY_KEEP_LAST, 34); /* W + 2: a producer runs up to W steps ahead */
      dds_qset_reliability(q, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_durability(q, DDS_DURABILITY_VOLATILE);
      break;
    case CL_OBSERVER: /* SimTime, viewer images */
      dds_qset_history(q, DDS_HISTORY_KEEP_LAST, 1);
      dds_qset_reliability(q, DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_durability(q, DDS_DURABILITY_VOLATILE);
      break;
  }
  return q;
}

/* Cyclone for the Fast DDS services: unicast discovery (SPDP to the well-known ports of the
 * domain's participant indices on 127.0.0.1), no multicast, the 4 s participant lease of
 * deploy/qos/climbsim.xml. Cyclone 0.10 bound to "lo" drops the Fast DDS participants: they
 * announce only the host's non-loopback address, so the default interface is kept (the traffic
 * goes to the host's own address and stays on it). */
static const char* kConfig =
    "<CycloneDDS><Domain id=\"any\">"
    "<General>"
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
    "<MaxAutoParticipantIndex>48</MaxAutoParticipantIndex>"
    "<Peers><Peer address=\"127.0.0.1\"/></Peers>"
    "<LeaseDuration>4s</LeaseDuration><SPDPInterval>200ms</SPDPInterval></Discovery>"
    "</Domain></CycloneDDS>";

static dds_entity_t make_endpoint(cl_participant* p, const char* topic_name, const dds_topic_descriptor_t* desc,
                                  cl_profile profile, bool writer) {
  const dds_entity_t topic = dds_create_topic(p->participant, desc, topic_name, NULL, NULL);
  if (topic < 0) {
    fprintf(stderr, "cannot create topic '%s': %s\n", topic_name, dds_strretcode(-topic));
    return topic;
  }
  dds_qos_t* q = cl_qos(profile, writer);
  const dds_entity_t e = writer ? dds_create_writer(p->participant, topic, q, NULL)
                                : dds_create_reader(p->participant, topic, q, NULL);
  dds_delete_qos(q);
  if (e < 0) {
    fprintf(stderr, "cannot create a %s of '%s': %s\n", writer ? "writer" : "reader", topic_name,
            dds_strretcode(-e));
    return e;
  }
  if (!writer) {
    /* Any sample in the reader wakes the waitset. */
    const dds_entity_t cond = dds_create_readcondition(e, DDS_ANY_STATE);
    dds_waitset_attach(p->waitset, cond, 0);
  }
  return e;
}

int cl_init(cl_participant* p, const char* name, int domain_id, uint32_t period_steps, uint32_t offset_steps,
            double start_timeout_s) {
  memset(p, 0, sizeof(*p));
  if (strlen(name) == 0 || strlen(name) > CL_MAX_NAME) {
    fprintf(stderr, "--name = '%s': a name is 1..%d characters\n", name, CL_MAX_NAME);
    return -1;
  }
  if (period_steps < 1 || offset_steps >= period_steps) {
    fprintf(stderr, "--period = %u, --offset = %u: need period >= 1 and offset < period\n", period_steps,
            offset_steps);
    return -1;
  }
  copy_name(p->name, sizeof(p->name), name);
  const char* run_id = getenv("CLIMBSIM_RUN_ID");
  if (run_id != NULL && run_id[0] != '\0') {
    char* end = NULL;
    p->expected_run_id = strtoull(run_id, &end, 10);
    if (*end != '\0' || run_id[0] == '-') {
      fprintf(stderr, "CLIMBSIM_RUN_ID = '%s': not a run id (an unsigned 64-bit number)\n", run_id);
      return -1;
    }
    p->has_expected_run_id = true;
  }
  p->period_steps = period_steps;
  p->offset_steps = offset_steps;
  p->start_timeout_s = start_timeout_s;
  p->domain = dds_create_domain((dds_domainid_t)domain_id, kConfig);
  if (p->domain < 0) {
    fprintf(stderr, "cannot create DDS domain %d: %s\n", domain_id, dds_strretcode(-p->domain));
    return -1;
  }
  p->participant = dds_create_participant((dds_domainid_t)domain_id, NULL, NULL);
  if (p->participant < 0) {
    fprintf(stderr, "cannot create a participant on domain %d: %s\n", domain_id, dds_strretcode(-p->participant));
    return -1;
  }
  p->waitset = dds_create_waitset(p->participant);
  p->data_guard = dds_create_guardcondition(p->participant);
  dds_waitset_attach(p->waitset, p->data_guard, 0);
  p->grant_reader = make_endpoint(p, CLIMBSIM_TOPIC_STEP_GRANT, &climbsim_StepGrant_desc, CL_CONTROL, false);
  p->run_start_reader = make_endpoint(p, CLIMBSIM_TOPIC_RUN_START, &climbsim_RunStart_desc, CL_LATCHED, false);
  p->stop_reader = make_endpoint(p, CLIMBSIM_TOPIC_STOP, &climbsim_Stop_desc, CL_LATCHED, false);
  p->done_writer = make_endpoint(p, CLIMBSIM_TOPIC_STEP_DONE, &climbsim_StepDone_desc, CL_CONTROL, true);
  p->ready_writer = make_endpoint(p, CLIMBSIM_TOPIC_PARTICIPANT_READY, &climbsim_ParticipantReady_desc, CL_LATCHED, true);
  if (p->grant_reader < 0 || p->run_start_reader < 0 || p->stop_reader < 0 || p->done_writer < 0 ||
      p->ready_writer < 0) {
    return -1;
  }
  return 0;
}

void cl_fini(cl_participant* p) {
  if (p->domain > 0) dds_delete(p->domain); /* first: no listener runs after this */
  p->domain = 0;
  for (size_t i = 0; i < p->n_inputs; ++i) {
    cl_input_port* port = &p->inputs[i];
    for (size_t k = 0; k < port->count; ++k) dds_sample_free(port->held[k], port->desc, DDS_FREE_ALL);
    for (size_t k = 0; k < port->n_arrivals; ++k) dds_sample_free(port->arrivals[k].sample, port->desc, DDS_FREE_ALL);
    free(port->arrivals);
    pthread_mutex_destroy(&port->lock);
  }
  if (p->run_start) dds_sample_free(p->run_start, &climbsim_RunStart_desc, DDS_FREE_ALL);
  if (p->stop) dds_sample_free(p->stop, &climbsim_Stop_desc, DDS_FREE_ALL);
  for (size_t i = 0; i < p->n_early; ++i) dds_sample_free(p->early_stops[i], &climbsim_Stop_desc, DDS_FREE_ALL);
}

/* Appends `sample` of `writer` to the port's arrivals, dropping that writer's oldest one if
 * it already has CL_PER_WRITER there. Call with port->lock held. */
static void add_arrival(cl_input_port* port, void* sample, dds_instance_handle_t writer) {
  size_t of_writer = 0, oldest = port->n_arrivals;
  for (size_t i = 0; i < port->n_arrivals; ++i) {
    if (port->arrivals[i].writer != writer) continue;
    if (of_writer++ == 0) oldest = i;
  }
  if (of_writer >= CL_PER_WRITER) {
    dds_sample_free(port->arrivals[oldest].sample, port->desc, DDS_FREE_ALL);
    memmove(&port->arrivals[oldest], &port->arrivals[oldest + 1],
            (port->n_arrivals - oldest - 1) * sizeof(cl_arrival));
    --port->n_arrivals;
  }
  if (port->n_arrivals == port->cap_arrivals) {
    const size_t cap = port->cap_arrivals == 0 ? 64 : 2 * port->cap_arrivals;
    cl_arrival* grown = realloc(port->arrivals, cap * sizeof(cl_arrival));
    if (grown == NULL) { /* out of memory: the sample is lost, as a full history would lose it */
      dds_sample_free(sample, port->desc, DDS_FREE_ALL);
      return;
    }
    port->arrivals = grown;
    port->cap_arrivals = cap;
  }
  port->arrivals[port->n_arrivals].sample = sample;
  port->arrivals[port->n_arrivals].writer = writer;
  ++port->n_arrivals;
}

static void* take_from(dds_entity_t reader, const dds_topic_descriptor_t* desc, size_t size,
                       dds_instance_handle_t* writer);

/* Moves whatever the reader holds into the port's arrivals (the listener, and before a drain).
 * Taken and queued under one lock: the listener's thread and the drain both take, and a sample
 * taken by one must not be queued after a later one taken by the other. */
static void take_arrivals(cl_input_port* port) {
  void* sample;
  dds_instance_handle_t writer = 0;
  bool any = false;
  pthread_mutex_lock(&port->lock);
  while ((sample = take_from(port->reader, port->desc, port->size, &writer)) != NULL) {
    add_arrival(port, sample, writer);
    any = true;
  }
  pthread_mutex_unlock(&port->lock);
  if (any) dds_set_guardcondition(port->wake, true);
}

static void on_data_available(dds_entity_t reader, void* arg) {
  (void)reader;
  take_arrivals((cl_input_port*)arg);
}

int cl_input(cl_participant* p, const char* topic, const dds_topic_descriptor_t* desc, size_t size) {
  if (p->n_inputs == CL_MAX_PORTS) return -1;
  cl_input_port* port = &p->inputs[p->n_inputs];
  port->topic = topic;
  port->desc = desc;
  port->size = size;
  port->wake = p->data_guard;
  pthread_mutex_init(&port->lock, NULL);
  const dds_entity_t t = dds_create_topic(p->participant, desc, topic, NULL, NULL);
  if (t < 0) {
    fprintf(stderr, "cannot create topic '%s': %s\n", topic, dds_strretcode(-t));
    return -1;
  }
  dds_qos_t* q = cl_qos(CL_STEP_DATA, false);
  dds_listener_t* listener = dds_create_listener(port);
  dds_lset_data_available(listener, on_data_available);
  port->reader = dds_create_reader(p->participant, t, q, listener);
  dds_delete_listener(listener);
  dds_delete_qos(q);
  if (port->reader < 0) {
    fprintf(stderr, "cannot create a reader of '%s': %s\n", topic, dds_strretcode(-port->reader));
    return -1;
  }
  take_arrivals(port); /* anything that came before the listener was set */
  return (int)p->n_inputs++;
}

int cl_output(cl_participant* p, const char* topic, const dds_topic_descriptor_t* desc) {
  if (p->n_outputs == CL_MAX_PORTS) return -1;
  cl_output_port* port = &p->outputs[p->n_outputs];
  port->topic = topic;
  port->writer = make_endpoint(p, topic, desc, CL_STEP_DATA, true);
  if (port->writer < 0) return -1;
  return (int)p->n_outputs++;
}

/* Takes the next valid sample of `reader` into a fresh dds_alloc'ed sample, or NULL; `writer`
 * (if not NULL) gets the publication handle of its writer. */
static void* take_from(dds_entity_t reader, const dds_topic_descriptor_t* desc, size_t size,
                       dds_instance_handle_t* writer) {
  while (true) {
    void* sample = dds_alloc(size);
    dds_sample_info_t info;
    const dds_return_t n = dds_take(reader, &sample, &info, 1, 1);
    if (n == 1 && info.valid_data) {
      if (writer != NULL) *writer = info.publication_handle;
      return sample;
    }
    dds_sample_free(sample, desc, DDS_FREE_ALL);
    if (n != 1) return NULL;
  }
}

/* The 12-byte GUID prefix of the DDS participant of a matched writer; false if unknown. */
static bool sender_of(dds_entity_t reader, dds_instance_handle_t writer, uint8_t prefix[12]) {
  dds_builtintopic_endpoint_t* data = dds_get_matched_publication_data(reader, writer);
  if (data == NULL) return false;
  memcpy(prefix, data->participant_key.v, 12);
  dds_builtintopic_free_endpoint(data);
  return true;
}

/* Counts a sample dropped because of its sender; logs the first one of each writer. */
static void drop_foreign(cl_participant* p, const char* topic, dds_instance_handle_t writer, const char* why) {
  ++p->dropped;
  for (size_t i = 0; i < p->n_logged; ++i) {
    if (p->logged[i] == writer) return;
  }
  if (p->n_logged < sizeof(p->logged) / sizeof(p->logged[0])) p->logged[p->n_logged++] = writer;
  fprintf(stderr, "%s: dropped a sample of '%s' from writer %llx: %s (counted, logged once per writer)\n", p->name,
          topic, (unsigned long long)writer, why);
}

/* The GUID prefix RunStart binds `participant` to; false if none. */
static bool identity_of(const climbsim_RunStart* rs, const char* participant, uint8_t prefix[12]) {
  for (uint32_t i = 0; i < rs->identities._length; ++i) {
    const climbsim_ParticipantIdentity* id = &rs->identities._buffer[i];
    if (strcmp(id->participant, participant) != 0 || strlen(id->guid_prefix) != 24) continue;
    for (int k = 0; k < 12; ++k) {
      unsigned byte = 0;
      if (sscanf(id->guid_prefix + 2 * k, "%2x", &byte) != 1) return false;
      prefix[k] = (uint8_t)byte;
    }
    return true;
  }
  return false;
}

static bool from_clock(cl_participant* p, dds_entity_t reader, dds_instance_handle_t writer, uint64_t run_id) {
  uint8_t prefix[12];
  const climbsim_RunStart* rs = p->run_start;
  return rs != NULL && run_id == rs->run_id && sender_of(reader, writer, prefix) &&
         memcmp(prefix, p->clock_id, 12) == 0;
}

static bool has_topic(const dds_sequence_string64* topics, const char* topic);

static void drain_input(cl_participant* p, cl_input_port* port) {
  const climbsim_RunStart* rs = p->run_start;
  if (rs == NULL) return; /* before the run start nobody's identity is known: the samples wait */
  take_arrivals(port);
  pthread_mutex_lock(&port->lock);
  cl_arrival* arrivals = port->arrivals;
  const size_t n = port->n_arrivals;
  port->arrivals = NULL;
  port->n_arrivals = port->cap_arrivals = 0;
  pthread_mutex_unlock(&port->lock);
  for (size_t a = 0; a < n; ++a) {
    void* sample = arrivals[a].sample;
    const dds_instance_handle_t writer = arrivals[a].writer;
    const stamp_head* h = sample;
    uint8_t claimed[12], sender[12];
    bool producer = false;
    for (uint32_t i = 0; i < rs->roster._length; ++i) {
      producer |= strcmp(rs->roster._buffer[i].participant, h->source) == 0 &&
                  has_topic(&rs->roster._buffer[i].output_topics, port->topic);
    }
    if (!producer || !identity_of(rs, h->source, claimed) || !sender_of(port->reader, writer, sender) ||
        memcmp(claimed, sender, 12) != 0) {
      drop_foreign(p, port->topic, writer, "not a writer of the producer it claims to be");
      dds_sample_free(sample, port->desc, DDS_FREE_ALL);
      continue;
    }
    if (port->count == CL_HELD) {
      dds_sample_free(port->held[0], port->desc, DDS_FREE_ALL);
      memmove(&port->held[0], &port->held[1], (CL_HELD - 1) * sizeof(void*));
      --port->count;
    }
    port->held[port->count++] = sample;
  }
  free(arrivals);
}

static int matched_writers(dds_entity_t reader) {
  dds_subscription_matched_status_t s;
  return dds_get_subscription_matched_status(reader, &s) == 0 ? (int)s.current_count : 0;
}

static int matched_readers(dds_entity_t writer) {
  dds_publication_matched_status_t s;
  return dds_get_publication_matched_status(writer, &s) == 0 ? (int)s.current_count : 0;
}

/* Takes `sample` (a RunStart from `writer`) as this run's if it is of the launcher's run id
 * and binds this participant to its own DDS participant: its sender is then the clock. */
static void take_run_start(cl_participant* p, void* sample, dds_instance_handle_t writer) {
  const climbsim_RunStart* rs = sample;
  uint8_t own[12], bound[12], sender[12];
  dds_guid_t guid;
  bool ours = p->run_start == NULL && (!p->has_expected_run_id || rs->run_id == p->expected_run_id) &&
              sender_of(p->run_start_reader, writer, sender) && dds_get_guid(p->participant, &guid) == 0;
  if (ours) {
    memcpy(own, guid.v, 12);
    for (uint32_t i = 0; ours && i < rs->roster._length; ++i) {
      const char* name = rs->roster._buffer[i].participant;
      ours = identity_of(rs, name, bound) && (strcmp(name, p->name) != 0 || memcmp(bound, own, 12) == 0);
    }
  }
  if (ours) {
    p->run_start = sample;
    memcpy(p->clock_id, sender, 12);
    return;
  }
  if (p->run_start == NULL || !from_clock(p, p->run_start_reader, writer, rs->run_id)) {
    drop_foreign(p, CLIMBSIM_TOPIC_RUN_START, writer, "not a RunStart of this run's clock");
  }
  dds_sample_free(sample, &climbsim_RunStart_desc, DDS_FREE_ALL);
}

static void poll_control(cl_participant* p) {
  void* sample;
  dds_instance_handle_t writer = 0;
  while ((sample = take_from(p->run_start_reader, &climbsim_RunStart_desc, sizeof(climbsim_RunStart), &writer)) !=
         NULL) {
    take_run_start(p, sample, writer);
  }
  /* Stops that came before the RunStart: judged now that it binds the clock. */
  for (size_t i = 0; p->run_start != NULL && i < p->n_early; ++i) {
    const climbsim_Stop* stop = p->early_stops[i];
    if (p->stop == NULL && p->early_sender_known[i] && stop->run_id == ((climbsim_RunStart*)p->run_start)->run_id &&
        memcmp(p->early_senders[i], p->clock_id, 12) == 0) {
      p->stop = p->early_stops[i];
      continue;
    }
    drop_foreign(p, CLIMBSIM_TOPIC_STOP, p->early_writers[i], "not a Stop of this run's clock");
    dds_sample_free(p->early_stops[i], &climbsim_Stop_desc, DDS_FREE_ALL);
  }
  if (p->run_start != NULL) p->n_early = 0;
  while ((sample = take_from(p->stop_reader, &climbsim_Stop_desc, sizeof(climbsim_Stop), &writer)) != NULL) {
    const climbsim_Stop* stop = sample;
    if (p->run_start == NULL && p->stop == NULL && p->n_early < CL_EARLY_STOPS) {
      /* Before RunStart nobody is bound as the clock: kept until it is, with its sender. */
      p->early_sender_known[p->n_early] = sender_of(p->stop_reader, writer, p->early_senders[p->n_early]);
      p->early_writers[p->n_early] = writer;
      p->early_stops[p->n_early++] = sample;
      continue;
    }
    const bool ours = p->run_start != NULL && from_clock(p, p->stop_reader, writer, stop->run_id);
    if (p->stop == NULL && ours) {
      p->stop = sample;
    } else {
      if (!ours) drop_foreign(p, CLIMBSIM_TOPIC_STOP, writer, "not a Stop of this run's clock");
      dds_sample_free(sample, &climbsim_Stop_desc, DDS_FREE_ALL);
    }
  }
  /* The clock left before any RunStart: it never made the run id public, so the first early
   * Stop of the launcher's run id is its (it stopped the run before starting it). */
  if (p->run_start == NULL && p->stop == NULL) {
    const int grant_writers = matched_writers(p->grant_reader);
    p->clock_seen = p->clock_seen || grant_writers > 0;
    for (size_t i = 0; p->clock_seen && grant_writers == 0 && p->has_expected_run_id && i < p->n_early; ++i) {
      if (((climbsim_Stop*)p->early_stops[i])->run_id == p->expected_run_id) {
        p->stop = p->early_stops[i];
        p->early_stops[i] = p->early_stops[--p->n_early];
        p->early_sender_known[i] = p->early_sender_known[p->n_early];
        memcpy(p->early_senders[i], p->early_senders[p->n_early], 12);
        p->early_writers[i] = p->early_writers[p->n_early];
        break;
      }
    }
  }
  for (size_t i = 0; i < p->n_inputs; ++i) drain_input(p, &p->inputs[i]);
}

static void wait_news(cl_participant* p) {
  dds_waitset_wait(p->waitset, NULL, 0, DDS_MSECS(50));
  /* Reset before the inputs are drained: what arrives later sets it again. */
  dds_set_guardcondition(p->data_guard, false);
}

static int exit_code_for_stop(const climbsim_Stop* stop) {
  if (stop->kind == climbsim_STOP_COMPLETED || stop->kind == climbsim_STOP_REQUESTED || stop->kind == climbsim_STOP_FELL) {
    fprintf(stderr, "run ended after step %llu: %s\n", (unsigned long long)stop->last_step, stop->reason);
    return CL_EXIT_OK;
  }
  fprintf(stderr, "run failed%s%s%s: %s\n", stop->culprit[0] ? " because of '" : "", stop->culprit,
          stop->culprit[0] ? "'" : "", stop->reason);
  return CL_EXIT_FAILED;
}

static void send_done(cl_participant* p, uint64_t step, climbsim_StepDoneKind kind, const char* message) {
  climbsim_StepDone done;
  memset(&done, 0, sizeof(done));
  copy_name(done.participant, sizeof(done.participant), p->name);
  done.run_id = p->run_start ? ((climbsim_RunStart*)p->run_start)->run_id : 0;
  done.progress_step = step;
  done.kind = kind;
  copy_name(done.message, sizeof(done.message), message);
  dds_write(p->done_writer, &done);
}

static bool has_topic(const dds_sequence_string64* topics, const char* topic) {
  for (uint32_t i = 0; i < topics->_length; ++i) {
    if (strcmp(topics->_buffer[i], topic) == 0) return true;
  }
  return false;
}

/* Roster entries that write `topic`, sorted by participant name (at most 32). */
static size_t producers(const cl_participant* p, const char* topic, const climbsim_RosterEntry** out) {
  const climbsim_RunStart* rs = p->run_start;
  size_t n = 0;
  if (rs == NULL) return 0;
  for (uint32_t i = 0; i < rs->roster._length && n < 32; ++i) {
    if (has_topic(&rs->roster._buffer[i].output_topics, topic)) {
      size_t k = n++;
      while (k > 0 && strcmp(out[k - 1]->participant, rs->roster._buffer[i].participant) > 0) {
        out[k] = out[k - 1];
        --k;
      }
      out[k] = &rs->roster._buffer[i];
    }
  }
  return n;
}

size_t cl_producer_count(const cl_participant* p, int input) {
  const climbsim_RosterEntry* found[32];
  return producers(p, p->inputs[input].topic, found);
}

/* Readers of `topic` from this participant: those reading every producer of it, and those
 * reading it from this one (input_sources "topic=name", idl/clock.idl); at most 32 in `out`. */
static size_t consumers(const cl_participant* p, const char* topic, const climbsim_RosterEntry** out) {
  const climbsim_RunStart* rs = p->run_start;
  const size_t topic_len = strlen(topic);
  size_t n = 0;
  for (uint32_t i = 0; i < rs->roster._length && n < 32; ++i) {
    const climbsim_RosterEntry* e = &rs->roster._buffer[i];
    if (!has_topic(&e->input_topics, topic)) continue;
    bool selective = false, selects_me = false;
    for (uint32_t j = 0; j < e->input_sources._length; ++j) {
      const char* source = e->input_sources._buffer[j];
      if (strncmp(source, topic, topic_len) == 0 && source[topic_len] == '=') {
        selective = true;
        selects_me = selects_me || strcmp(source + topic_len + 1, p->name) == 0;
      }
    }
    if (!selective || selects_me) out[n++] = e;
  }
  return n;
}

int cl_get(cl_participant* p, int input, size_t producer_index, const cl_step* s, const void** sample) {
  cl_input_port* port = &p->inputs[input];
  const climbsim_RosterEntry* found[32];
  const size_t n = producers(p, port->topic, found);
  *sample = NULL;
  if (producer_index >= n) return -1;
  const climbsim_RosterEntry* e = found[producer_index];
  /* The producer's last due step before s->step (zero-order hold). */
  if (s->step <= e->offset_steps) return 0;
  const uint64_t since_first = s->step - 1 - e->offset_steps;
  const uint64_t stamp = e->offset_steps + since_first - since_first % e->period_steps;
  while (p->stop == NULL) {
    poll_control(p);
    bool later = false;
    for (size_t k = 0; k < port->count; ++k) {
      const stamp_head* h = port->held[k];
      if (strcmp(h->source, e->participant) != 0) continue;
      if (h->step == stamp) {
        *sample = h;
        return 0;
      }
      later = later || h->step > stamp;
    }
    if (later) {
      fprintf(stderr, "topic '%s': the sample of '%s' stamped %llu is missing\n", port->topic, e->participant,
              (unsigned long long)stamp);
      return -1;
    }
    wait_news(p);
  }
  return -1;
}

int cl_write(cl_participant* p, int output, void* sample, const cl_step* s) {
  stamp_head* h = sample;
  copy_name(h->source, sizeof(h->source), p->name);
  h->step = s->step;
  h->t_ns = s->t_ns;
  const dds_return_t rc = dds_write(p->outputs[output].writer, sample);
  if (rc != 0) fprintf(stderr, "writing to '%s' failed: %s\n", p->outputs[output].topic, dds_strretcode(-rc));
  return rc;
}

static void announce_ready(cl_participant* p) {
  char inputs[CL_MAX_PORTS][65];
  char outputs[CL_MAX_PORTS][65];
  climbsim_IdlHash hashes[sizeof(cl_idl_hashes) / sizeof(cl_idl_hashes[0])];
  climbsim_ParticipantReady ready;
  memset(&ready, 0, sizeof(ready));
  copy_name(ready.participant, sizeof(ready.participant), p->name);
  copy_name(ready.entry.participant, sizeof(ready.entry.participant), p->name);
  ready.entry.period_steps = p->period_steps;
  ready.entry.offset_steps = p->offset_steps;
  for (size_t i = 0; i < p->n_inputs; ++i) copy_name(inputs[i], sizeof(inputs[i]), p->inputs[i].topic);
  for (size_t i = 0; i < p->n_outputs; ++i) copy_name(outputs[i], sizeof(outputs[i]), p->outputs[i].topic);
  ready.entry.input_topics._length = ready.entry.input_topics._maximum = (uint32_t)p->n_inputs;
  ready.entry.input_topics._buffer = inputs;
  ready.entry.output_topics._length = ready.entry.output_topics._maximum = (uint32_t)p->n_outputs;
  ready.entry.output_topics._buffer = outputs;
  for (size_t i = 0; i < sizeof(cl_idl_hashes) / sizeof(cl_idl_hashes[0]); ++i) {
    copy_name(hashes[i].file, sizeof(hashes[i].file), cl_idl_hashes[i][0]);
    copy_name(hashes[i].sha256, sizeof(hashes[i].sha256), cl_idl_hashes[i][1]);
  }
  ready.idl_hashes._length = ready.idl_hashes._maximum = sizeof(hashes) / sizeof(hashes[0]);
  ready.idl_hashes._buffer = hashes;
  char host[256] = {0};
  if (gethostname(host, sizeof(host) - 1) != 0) copy_name(host, sizeof(host), "unknown");
  copy_name(ready.host, sizeof(ready.host), host);
  ready.pid = (uint32_t)getpid();
  dds_write(p->ready_writer, &ready);
}

/* Waits (polling the control plane) until `cond` holds; 1 = yes, 0 = stopped, -1 = timeout. */
static int wait_until(cl_participant* p, bool (*cond)(cl_participant*), dds_time_t deadline, const char* what) {
  while (true) {
    poll_control(p);
    if (cond(p)) return 1;
    if (p->stop != NULL) return 0;
    if (now_ns() >= deadline) {
      fprintf(stderr, "timed out after %g s waiting for %s\n", p->start_timeout_s, what);
      return -1;
    }
    wait_news(p);
  }
}

static bool clock_matched(cl_participant* p) {
  return matched_writers(p->grant_reader) > 0 && matched_readers(p->done_writer) > 0;
}

static bool run_started(cl_participant* p) { return p->run_start != NULL; }

/* Whether a writer matched by `reader` (or a reader matched by writer `writer`; the other is 0)
 * belongs to the DDS participant of GUID prefix `want`. */
static bool matched_prefix(dds_entity_t reader, dds_entity_t writer, const uint8_t want[12]) {
  dds_instance_handle_t some[64];
  dds_instance_handle_t* handles = some;
  size_t room = sizeof(some) / sizeof(some[0]);
  dds_return_t n = reader ? dds_get_matched_publications(reader, handles, room)
                          : dds_get_matched_subscriptions(writer, handles, room);
  if (n > (dds_return_t)room) { /* more endpoints than the stack holds (an outsider's flood) */
    room = (size_t)n;
    handles = malloc(room * sizeof(*handles));
    if (handles == NULL) return false;
    n = reader ? dds_get_matched_publications(reader, handles, room) : dds_get_matched_subscriptions(writer, handles, room);
  }
  bool found = false;
  for (dds_return_t i = 0; i < n && (size_t)i < room && !found; ++i) {
    dds_builtintopic_endpoint_t* data = reader ? dds_get_matched_publication_data(reader, handles[i])
                                               : dds_get_matched_subscription_data(writer, handles[i]);
    if (data == NULL) continue; /* unmatched meanwhile */
    found = memcmp(data->participant_key.v, want, 12) == 0;
    dds_builtintopic_free_endpoint(data);
  }
  if (handles != some) free(handles);
  return found;
}

/* As matched_prefix, for the DDS participant RunStart binds `participant` to. */
static bool matched_by_identity(const cl_participant* p, dds_entity_t reader, dds_entity_t writer,
                                const char* participant) {
  uint8_t want[12];
  return identity_of(p->run_start, participant, want) && matched_prefix(reader, writer, want);
}

/* Every producer of every input and every consumer of every output matched, by identity, not
 * counted: a writer or reader of the topic that is not on the roster (an outsider's, a plain
 * DDS observer's) must not stand in for a roster member whose endpoint has not matched yet, or
 * that member misses the first samples (VOLATILE) and the run waits for them until the watchdog. */
static bool data_matched(cl_participant* p) {
  /* The clock, too: its StepDone reader must have matched before ARMED is written. */
  if (!matched_prefix(p->grant_reader, 0, p->clock_id) || !matched_prefix(0, p->done_writer, p->clock_id)) return false;
  const climbsim_RosterEntry* found[32];
  for (size_t i = 0; i < p->n_inputs; ++i) {
    const size_t n = producers(p, p->inputs[i].topic, found);
    for (size_t k = 0; k < n; ++k) {
      if (!matched_by_identity(p, p->inputs[i].reader, 0, found[k]->participant)) return false;
    }
  }
  for (size_t i = 0; i < p->n_outputs; ++i) {
    const size_t n = consumers(p, p->outputs[i].topic, found);
    for (size_t k = 0; k < n; ++k) {
      if (!matched_by_identity(p, 0, p->outputs[i].writer, found[k]->participant)) return false;
    }
  }
  return true;
}

static int fail_run(cl_participant* p, const char* message) {
  fprintf(stderr, "%s\n", message);
  send_done(p, p->current_step, climbsim_FAILED, message);
  const dds_time_t deadline = now_ns() + FAILURE_LINGER_NS;
  while (p->stop == NULL && now_ns() < deadline) {
    poll_control(p);
    wait_news(p);
  }
  return CL_EXIT_FAILED;
}

int cl_run(cl_participant* p, cl_step_fn fn, void* user) {
  const dds_time_t deadline = now_ns() + (dds_time_t)(p->start_timeout_s * 1e9);
  int r = wait_until(p, clock_matched, deadline, "the clock");
  if (r < 0) return CL_EXIT_FAILED;
  announce_ready(p);
  fprintf(stderr, "%s: ready (period %u offset %u), waiting for the run to start\n", p->name, p->period_steps,
          p->offset_steps);
  if (r > 0) r = wait_until(p, run_started, deadline, "the run to start");
  if (r < 0) return CL_EXIT_FAILED;
  if (r > 0) {
    const climbsim_RunStart* rs = p->run_start;
    bool on_roster = false;
    for (uint32_t i = 0; i < rs->roster._length; ++i) on_roster |= strcmp(rs->roster._buffer[i].participant, p->name) == 0;
    if (!on_roster) return fail_run(p, "the run started without this participant on its roster");
    r = wait_until(p, data_matched, deadline, "the data topics to match their producers and consumers");
    if (r < 0) return fail_run(p, "the data topics did not match their producers and consumers in time");
  }
  if (r > 0) send_done(p, 0, climbsim_ARMED, "");
  const climbsim_RunStart* rs = p->run_start;
  for (uint32_t i = 0; r > 0 && i < rs->roster._length; ++i) {
    for (size_t o = 0; o < p->n_outputs; ++o) {
      if (has_topic(&rs->roster._buffer[i].recorded_topics, p->outputs[o].topic)) {
        return fail_run(p, "a recorder reads this client's output through record batches, which the C client "
                           "does not write; record another topic or use a C++ producer");
      }
    }
  }
  /* The horizon protocol (docs/design.md#horizons): compute every due step below the horizon in
   * order, each once its stamped inputs are there; report progress every W/2 steps and at
   * the horizon. */
  const uint64_t end_step = rs->end_step;
  const uint64_t stride = rs->window_steps / 2 > 0 ? rs->window_steps / 2 : 1;
  uint64_t horizon = 0;
  uint64_t progress = p->offset_steps < end_step ? p->offset_steps : end_step;
  uint64_t acked = progress;
  while (p->stop == NULL) {
    poll_control(p);
    void* sample;
    dds_instance_handle_t writer = 0;
    while ((sample = take_from(p->grant_reader, &climbsim_StepGrant_desc, sizeof(climbsim_StepGrant), &writer)) !=
           NULL) {
      const climbsim_StepGrant* grant = sample;
      if (!from_clock(p, p->grant_reader, writer, grant->run_id)) {
        drop_foreign(p, CLIMBSIM_TOPIC_STEP_GRANT, writer, "not a StepGrant of this run's clock");
      } else if (grant->horizon_step > horizon) {
        horizon = grant->horizon_step;
      }
      dds_sample_free(sample, &climbsim_StepGrant_desc, DDS_FREE_ALL);
    }
    if (progress < horizon && progress < end_step) {
      const cl_step s = {progress, (int64_t)progress * rs->dt_ns, rs->dt_ns};
      char why[256] = {0};
      p->current_step = progress;
      p->in_step = true;
      if (fn(p, &s, user, why, sizeof(why)) != 0) {
        if (p->stop != NULL) break; /* the run ended while the step waited for its inputs */
        char message[300];
        snprintf(message, sizeof(message), "step %llu: %s", (unsigned long long)progress, why);
        return fail_run(p, message);
      }
      p->in_step = false;
      progress += p->period_steps;
      if (progress > end_step) progress = end_step;
      if (progress - acked >= stride) {
        send_done(p, progress, climbsim_STEP_DONE, "");
        acked = progress;
      }
      continue;
    }
    if (progress > acked) {
      send_done(p, progress, climbsim_STEP_DONE, "");
      acked = progress;
    }
    if (matched_writers(p->grant_reader) == 0) {
      fprintf(stderr, "the clock vanished without stopping the run\n");
      return CL_EXIT_FAILED;
    }
    wait_news(p);
  }
  return exit_code_for_stop(p->stop);
}
