import climbsim_idl as idl
from climbsim import topics
from climbsim.cli import participant

p = participant("mycontroller")          # --name --period --offset --domain as the launcher appends them
forces = p.input(topics.ADHESION_FORCE, idl.AdhesionForce)
valves = p.output(topics.VALVE_COMMAND, idl.ValveCommand)
SETPOINT_N = 2200.0                      # F* [N]: sent with the valves, the plots show it

def step(ctx):                           # ctx.step, ctx.t_ns, ctx.dt_ns
    f = forces.get(ctx)                  # thermo's sample of the step before, waited for
    opening = 0.5 if f and f[0].downforce_n < SETPOINT_N else 0.0
    n = len(p.run_start.robot.chambers)  # the run's robot (RunStart): one valve per chamber
    valves.write(ctx, idl.ValveCommand(opening=[opening] * n, downforce_setpoint_n=SETPOINT_N))  # stamps set

raise SystemExit(p.run(step))            # 0 completed, 1 failed, 2 bad configuration
