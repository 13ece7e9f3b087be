"""`deploy/climbsim setup` finds the missing Debian packages and installs exactly those.

dpkg-query and apt-get are stand-ins on PATH (the real ones would change the machine): the
stand-in dpkg-query answers from a state file as dpkg-query -W does (a package it does not know
is left out, with an error on stderr), the stand-in apt-get records its calls and marks what it
installs in the state file.
"""

import os
import pathlib
import re
import stat
import subprocess
import sys
import tempfile
import unittest

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[3])
CLIMBSIM = ROOT / "deploy" / "climbsim"

FAKE_DPKG_QUERY = r"""#!/usr/bin/env bash
# dpkg-query -W -f=FORMAT PKG...: one line per package the state file knows.
shift 2
status=0
for pkg in "$@"; do
  line="$(awk -v p="$pkg" '$1 == p' "$STATE")"
  if [[ -z "$line" ]]; then
    echo "dpkg-query: no packages found matching $pkg" >&2
    status=1
  else
    echo "$line"
  fi
done
exit $status
"""

FAKE_APT_GET = r"""#!/usr/bin/env bash
echo "$*" >> "$CALLS"
if [[ "$1" == "install" && -z "${APT_FAILS:-}" ]]; then
  for pkg in "$@"; do
    [[ "$pkg" == -* || "$pkg" == install ]] && continue
    awk -v p="$pkg" '$1 != p' "$STATE" > "$STATE.new" && mv "$STATE.new" "$STATE"
    echo "$pkg install ok installed" >> "$STATE"
  done
fi
[[ -z "${APT_FAILS:-}" ]]
"""


def shipped_packages():
    text = CLIMBSIM.read_text()
    block = text[text.index("PACKAGES=(") : text.index("\n)\n", text.index("PACKAGES=("))]
    return re.findall(r'^\s+"([^ "]+)', block, re.M)


class Setup(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        d = pathlib.Path(self.dir.name)
        for name, text in (("dpkg-query", FAKE_DPKG_QUERY), ("apt-get", FAKE_APT_GET)):
            path = d / name
            path.write_text(text)
            path.chmod(path.stat().st_mode | stat.S_IXUSR)
        self.state = d / "state"
        self.calls = d / "calls"
        self.calls.write_text("")
        self.env = dict(os.environ, PATH=f"{d}:{os.environ['PATH']}", STATE=str(self.state), CALLS=str(self.calls))
        self.packages = shipped_packages()
        self.assertGreater(len(self.packages), 20)

    def tearDown(self):
        self.dir.cleanup()

    def write_state(self, lines):
        self.state.write_text("".join(line + "\n" for line in lines))

    def setup(self, **extra):
        if os.geteuid() != 0:
            self.skipTest("setup installs as root or through sudo; this runs as another user")
        return subprocess.run([str(CLIMBSIM), "setup"], env=dict(self.env, **extra), capture_output=True, text=True,
                              timeout=60)

    def test_every_package_installed_installs_nothing(self):
        self.write_state(f"{p} install ok installed" for p in self.packages)
        run = self.setup()
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn(f"all {len(self.packages)} Debian packages are installed", run.stderr)
        self.assertEqual(self.calls.read_text(), "")

    def test_the_missing_packages_and_only_they_are_installed(self):
        # One unknown to dpkg, one removed with its configuration kept, the others installed.
        unknown, removed = self.packages[3], self.packages[7]
        self.write_state(
            [f"{p} install ok installed" for p in self.packages if p not in (unknown, removed)]
            + [f"{removed} deinstall ok config-files"]
        )
        run = self.setup()
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn(f"installing missing Debian packages: {unknown} {removed}", run.stderr)
        calls = self.calls.read_text().splitlines()
        self.assertEqual(calls[0].split()[0], "update")
        self.assertEqual(calls[1].split()[0], "install")
        self.assertEqual([w for w in calls[1].split()[1:] if not w.startswith("-")], [unknown, removed])
        self.assertIn("setup: done", run.stderr)

    def test_a_failed_install_is_one_error_line_and_a_non_zero_exit(self):
        missing = self.packages[0]
        self.write_state(f"{p} install ok installed" for p in self.packages if p != missing)
        run = self.setup(APT_FAILS="1")
        self.assertNotEqual(run.returncode, 0)
        self.assertRegex(run.stderr, r"climbsim: error: setup: 'apt-get (update|install [^']*)' failed")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
