"""The command line the launcher gives every program of a compose file.

The launcher appends ``--name NAME --period N --offset K --domain D`` to each service's command
(docs/controllers.md#joining-the-clock-any-language). A script that builds its participant with
:func:`participant` runs unchanged by hand (``--domain`` or ``$CLIMBSIM_DOMAIN``) and under the
launcher::

    from climbsim.cli import participant
    p = participant("mycontroller")     # name, schedule and domain from the command line

Bad options exit with code 2 and one line, like every climbsim program.
"""

from __future__ import annotations

import argparse
import sys
from typing import Sequence

from .dds import ConfigError
from .lockstep import EXIT_CONFIG, LockstepParticipant, Schedule, add_participant_options


def participant_options(default_name: str, argv: Sequence[str] | None = None,
                        description: str | None = None,
                        parser: argparse.ArgumentParser | None = None,
                        period_steps: int = 1, offset_steps: int = 0) -> argparse.Namespace:
    """Parses --name (default `default_name`), --period, --offset (defaults `period_steps`,
    `offset_steps`), --start-timeout-s, --domain and --qos from `argv` (default: sys.argv[1:])
    with `parser` (a new one if None; add your own options to it first). Unknown options are
    an error (exit 2)."""
    if parser is None:
        parser = argparse.ArgumentParser(description=description)
    add_participant_options(parser)
    parser.set_defaults(name=default_name, period=period_steps, offset=offset_steps)
    for action in parser._actions:  # --name is required for services; a script has a default
        if action.dest == "name":
            action.required = False
    return parser.parse_args(argv)


def participant(default_name: str, period_steps: int = 1, offset_steps: int = 0,
                argv: Sequence[str] | None = None) -> LockstepParticipant:
    """A LockstepParticipant named, scheduled and placed on a domain as the command line says
    (the launcher's --name, --period, --offset, --domain), else `default_name`, `period_steps`,
    `offset_steps` and $CLIMBSIM_DOMAIN. A bad option or value exits with code 2."""
    parser = argparse.ArgumentParser()
    args = participant_options(default_name, argv, parser=parser, period_steps=period_steps, offset_steps=offset_steps)
    try:
        return LockstepParticipant(args.name, args.domain, Schedule(args.period, args.offset), args.start_timeout_s)
    except ConfigError as e:
        print(f"{parser.prog}: error: {e}", file=sys.stderr)
        raise SystemExit(EXIT_CONFIG) from None
