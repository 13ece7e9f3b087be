import climbsim_idl as idl
from climbsim import topics
from climbsim.cli import participant

p = participant("mycontroller")          # --name --period --offset --domain as the launcher appends them
forces = p.input(topics.ADHESION_FORCE, idl.AdhesionForce)
valves = p.output(topics.VALVE_COMMAND, idl.ValveCommand)

def step(ctx):                           # ctx.step, ctx.t_ns, ctx.dt_ns
    f = forces.get(ctx)                  # thermo's sample of the step before, waited for
    opening = 0.5 if f and f[0].downforce_n < 2200 else 0.0
    valves.write(ctx, idl.ValveCommand(opening=[opening] * 7))  # source, step, t_ns set

raise SystemExit(p.run(step))            # 0 completed, 1 failed, 2 bad configuration
