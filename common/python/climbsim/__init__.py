"""climbsim's Python runtime on Cyclone DDS: message types generated from idl/ at build time
(module climbsim_idl, by climbsim.idlgen), the QoS of deploy/qos/climbsim.xml (climbsim.qos),
topic names (climbsim.topics) and the lockstep participant protocol (climbsim.lockstep).

The generated module lives in <build>/python; the wrapper scripts in <build>/bin put it and
this package on the path. Run tools through <build>/venv/bin/python.
"""
