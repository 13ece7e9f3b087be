"""climbsim.lockstep.Schedule agrees with its definition (as common/src/schedule.cpp)."""

import unittest

from climbsim.dds import ConfigError, parse_domain_id
from climbsim.lockstep import Schedule, validate_name


class ScheduleTest(unittest.TestCase):
    def test_due_steps_and_last_due_before_match_brute_force(self):
        for period in (1, 2, 4, 7):
            for offset in range(period):
                s = Schedule(period, offset)
                due = [k for k in range(60) if s.is_due(k)]
                self.assertEqual(due, list(range(offset, 60, period)))
                for step in range(60):
                    earlier = [k for k in due if k < step]
                    self.assertEqual(s.last_due_before(step), earlier[-1] if earlier else None)

    def test_bad_schedules_and_names_are_config_errors_naming_the_value(self):
        with self.assertRaisesRegex(ConfigError, "offset_steps = 4"):
            Schedule(4, 4).validate("p")
        with self.assertRaisesRegex(ConfigError, "period_steps = 0"):
            Schedule(0, 0).validate("p")
        with self.assertRaisesRegex(ConfigError, "character ' '"):
            validate_name("--name", "a b")
        with self.assertRaisesRegex(ConfigError, "out of range"):
            parse_domain_id("--domain", "233")


if __name__ == "__main__":
    unittest.main()
