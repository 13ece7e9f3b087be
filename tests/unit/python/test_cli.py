"""climbsim.cli: the options the launcher appends to every service command."""

import contextlib
import io
import unittest

from climbsim import cli


class ParticipantOptions(unittest.TestCase):
    def test_the_launchers_options_are_taken(self):
        args = cli.participant_options("mine", ["--name", "valves", "--period", "4", "--offset", "1", "--domain", "17"])
        self.assertEqual((args.name, args.period, args.offset, args.domain), ("valves", 4, 1, "17"))

    def test_by_hand_the_defaults_hold(self):
        args = cli.participant_options("mine", [], period_steps=2, offset_steps=1)
        self.assertEqual((args.name, args.period, args.offset, args.domain), ("mine", 2, 1, None))

    def test_an_unknown_option_exits_with_code_2(self):
        with contextlib.redirect_stderr(io.StringIO()), self.assertRaises(SystemExit) as e:
            cli.participant_options("mine", ["--colour", "red"])
        self.assertEqual(e.exception.code, 2)

    def test_a_bad_schedule_exits_with_code_2_and_one_line(self):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as e:
            cli.participant("mine", argv=["--period", "2", "--offset", "5", "--domain", "17"])
        self.assertEqual(e.exception.code, 2)
        self.assertEqual(len(err.getvalue().strip().splitlines()), 1, err.getvalue())


if __name__ == "__main__":
    unittest.main()
