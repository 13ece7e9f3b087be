"""The documents' tools can fail: the reference checker (docs/tools/check_references.py) on a
small tree with broken references, and the benchmark table (docs/tools/bench_table.py) on a
table edited by hand.

    python3 docs_tools_test.py ROOT
"""

import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

# The checkout: the argument (ctest), else this file's (pytest passes its own arguments).
ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 and Path(sys.argv[1]).is_dir() else Path(__file__).resolve().parents[3]
CHECKER = ROOT / "docs" / "tools" / "check_references.py"
TABLE = ROOT / "docs" / "tools" / "bench_table.py"

# Built from parts, so that this file holds no reference the checker would follow.
DOCS = "docs" + "/"
OUTSIDE_DESIGN = "DESIGN" + ".md"
MD = ".md"
README = "READ" + "ME"

GUIDE = """# Guide

## The loop
## Physics
### Airflow and downforce
## Notes
## Notes
## `Topics` and QoS (table)
"""


def run(*args):
    return subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True)


class ReferenceChecker(unittest.TestCase):
    def tree(self, files):
        folder = Path(tempfile.mkdtemp(prefix="climbsim-refs-"))
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", str(folder)]))
        for name, text in files.items():
            (folder / name).parent.mkdir(parents=True, exist_ok=True)
            (folder / name).write_text(text)
        return folder

    def check(self, files):
        return run(CHECKER, "--root", self.tree(files))

    def test_a_tree_whose_references_resolve_passes(self):
        result = self.check({
            DOCS + "guide.md": GUIDE + f"\nSee [airflow](#airflow-and-downforce), [more](other{MD}#more).\n",
            DOCS + "other.md": f"# Other\n\n## More\n\nBack to [the loop](guide{MD}#the-loop).\n",
            "src/model.cpp": f"// {DOCS}guide.md#airflow-and-downforce, {DOCS}guide.md#notes-1\n"
                             f"// {DOCS}guide.md#topics-and-qos-table and {DOCS}other.md\n",
            "README.md": f"Read [the guide]({DOCS}guide.md#physics).\n",
        })
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)

    def test_a_missing_document_is_named_with_file_and_line(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "src/model.cpp": f"int x;\n// see {DOCS}missing.md#the-loop\n",
        })
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"src/model.cpp:2: reference '{DOCS}missing.md#the-loop': no such document", result.stdout)

    def test_a_missing_heading_is_named(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "CMakeLists.txt": f"# {DOCS}guide.md#the-clock\n",
        })
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"CMakeLists.txt:1: reference '{DOCS}guide.md#the-clock': no heading with the anchor "
                      f"'the-clock' in {DOCS}guide.md", result.stdout)

    def test_a_third_duplicate_heading_has_no_anchor(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "a.py": f"# {DOCS}guide.md#notes-2\n",
        })
        self.assertEqual(result.returncode, 1)
        self.assertIn("'notes-2'", result.stdout)

    def test_a_heading_inside_a_code_block_is_no_anchor(self):
        result = self.check({
            DOCS + "guide.md": "# Guide\n\n```\n## Not a heading\n```\n",
            "a.hpp": f"/// {DOCS}guide.md#not-a-heading\n",
        })
        self.assertEqual(result.returncode, 1)

    def test_broken_links_inside_the_documents_are_named(self):
        result = self.check({
            DOCS + "guide.md": GUIDE + f"\n[a](#nowhere) [b](other{MD}) [c](other{MD}#less) [d](../{README}{MD})\n",
            DOCS + "other.md": "# Other\n\n## More\n",
            "README.md": "# Readme\n",
        })
        self.assertEqual(result.returncode, 1)
        lines = result.stdout.splitlines()
        self.assertEqual(len(lines), 2, result.stdout)
        self.assertIn(f"{DOCS}guide.md:10: reference '#nowhere'", lines[0])
        self.assertIn(f"{DOCS}guide.md:10: reference 'other.md#less'", lines[1])

    def test_a_link_from_a_document_resolves_against_its_own_folder(self):
        # Inside the docs folder a link to "<docs folder>/guide.md" names <docs folder>/<docs folder>/guide.md.
        result = self.check({DOCS + "guide.md": GUIDE + f"\n[self]({DOCS}guide.md)\n"})
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"reference '{DOCS}guide.md': no such document", result.stdout)

    def test_a_mention_of_the_outside_design_document_fails(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "services/x/main.cpp": f"// the loop ({OUTSIDE_DESIGN} §1)\n",
        })
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"services/x/main.cpp:1: reference '{OUTSIDE_DESIGN}'", result.stdout)

    def test_citations_of_readme_headings_that_exist_pass(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "README.md": "# climbsim\n\n## The two commands\n\n### A controller in Python\n",
            "a.cpp": f'// the test command ({README} "The two commands")\n',
            "b.xml": f'<!-- (see {README}{MD}, "the TWO commands!") -->\n',
            "c.py": f'"""The {README}\'s "A controller in Python" runs verbatim."""\n',
            "d.yaml": f'# the example ({README} "A controller in\n# Python")\n',
        })
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)

    def test_a_citation_of_a_missing_readme_heading_is_named(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "README.md": "# climbsim\n\n## The two commands\n",
            "a.cpp": f'int x;\n// the horizon ({README} "The clock")\n',
            "b.xml": f'<!-- (see {README}{MD}, "QoS") -->\n',
            "c.py": f'# the {README}\'s "Drive service"\n',
            "d.yaml": f'# flooding chambers ({README} "Several leaks flooding the\n# reservoir together")\n',
        })
        self.assertEqual(result.returncode, 1)
        lines = result.stdout.splitlines()
        self.assertEqual(len(lines), 4, result.stdout)
        self.assertEqual(lines[0], f"a.cpp:2: reference '{README} \"The clock\"': no heading 'The clock' in {README}{MD}")
        self.assertIn(f"b.xml:1: reference '{README} \"QoS\"'", lines[1])
        self.assertIn(f"c.py:1: reference '{README} \"Drive service\"'", lines[2])
        self.assertIn(f"d.yaml:1: reference '{README} \"Several leaks flooding the reservoir together\"'", lines[3])

    def test_paths_of_markdown_files_that_exist_pass(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "README.md": "# climbsim\n\n## The two commands\n",
            "services/x/README.md": "# x\n\n## Speeds\n",
            "services/x/NOTES.md": "# notes\n",
            "services/x/a.hpp": f"/// services/x/{README}{MD}#speeds, {README}{MD}#the-two-commands, NOTES{MD}\n",
            "tests/t.py": f'doc = folder / "made-up{MD}"\nother = "$ROOT/made-up{MD}"\n',
        })
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)

    def test_a_missing_markdown_file_or_heading_is_named(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "services/x/README.md": "# x\n\n## Speeds\n",
            "services/thermo/params.hpp": f"int x;\n/// monotone on decaying modes (INTEGRATOR{MD})\n",
            "b.cpp": f"// services/x/{README}{MD}#timings\n",
        })
        self.assertEqual(result.returncode, 1)
        lines = result.stdout.splitlines()
        self.assertEqual(len(lines), 2, result.stdout)
        self.assertEqual(lines[0], f"b.cpp:1: reference 'services/x/{README}{MD}#timings': no heading with the anchor "
                                   f"'timings' in services/x/{README}{MD}")
        self.assertEqual(lines[1], f"services/thermo/params.hpp:2: reference 'INTEGRATOR{MD}': no such file")

    def test_build_folders_are_not_scanned(self):
        result = self.check({
            DOCS + "guide.md": GUIDE,
            "build/generated.hpp": f"// {DOCS}missing.md\n",
        })
        self.assertEqual(result.returncode, 0, result.stdout)


class BenchTable(unittest.TestCase):
    def document(self):
        folder = Path(tempfile.mkdtemp(prefix="climbsim-bench-table-"))
        self.addCleanup(lambda: subprocess.run(["rm", "-rf", str(folder)]))
        doc = folder / "benchmarks.md"
        doc.write_text("# Benchmarks\n\n<!-- bench-table:begin -->\n<!-- bench-table:end -->\n\n## After\n")
        bench = folder / "bench"
        bench.mkdir()
        return doc, bench

    def test_figures_come_from_the_json_and_the_rest_is_not_measured(self):
        doc, bench = self.document()
        (bench / "drive.json").write_text(json.dumps({"name": "drive", "realtime_factor": 61.25}))
        (bench / "thermo.json").write_text(json.dumps({"scenarios": [
            {"scenario": "moving_valves", "realtime_factor": 812.4}]}))
        result = run(TABLE, "--bench-dir", bench, "--doc", doc)
        self.assertEqual(result.returncode, 0, result.stderr)
        text = doc.read_text()
        self.assertIn("| drive | `realtime_factor` | 61.2x |", text)
        self.assertRegex(text, r"\| drive \| `realtime_factor` \| 61\.2x \|[^\n]*\| ≥ 50x \| yes \|")
        self.assertRegex(text, r"\| thermo \| `realtime_factor \(moving valves\)` \| 812x \|[^\n]*\| no \|")
        self.assertIn("| e2e | `realtime_factor` | not measured in this table's run |", text)
        self.assertTrue(text.startswith("# Benchmarks\n") and text.endswith("## After\n"))
        self.assertEqual(run(TABLE, "--check", "--doc", doc).returncode, 0)

    def test_a_figure_edited_by_hand_fails_the_check(self):
        doc, bench = self.document()
        (bench / "drive.json").write_text(json.dumps({"realtime_factor": 61.25}))
        self.assertEqual(run(TABLE, "--bench-dir", bench, "--doc", doc).returncode, 0)
        # A faster figure typed in without its "met" cell, and a row typed in by hand.
        edited = doc.read_text().replace("| 61.2x |", "| 45.0x |")
        doc.write_text(edited)
        result = run(TABLE, "--check", "--doc", doc)
        self.assertEqual(result.returncode, 1)
        self.assertIn("differs from the script's rendering", result.stdout)
        doc.write_text(edited.replace("| 45.0x |", "| about 60x |"))
        self.assertEqual(run(TABLE, "--check", "--doc", doc).returncode, 1)

    def test_only_rewrites_that_benchmarks_rows_and_keeps_the_others(self):
        doc, bench = self.document()
        (bench / "drive.json").write_text(json.dumps({"realtime_factor": 61.25}))
        self.assertEqual(run(TABLE, "--bench-dir", bench, "--doc", doc).returncode, 0)
        (bench / "drive.json").unlink()
        (bench / "e2e.json").write_text(json.dumps({"recording": {"recording_cost": 0.0123}}))
        result = run(TABLE, "--only", "e2e", "--bench-dir", bench, "--doc", doc)
        self.assertEqual(result.returncode, 0, result.stderr)
        text = doc.read_text()
        self.assertIn("| drive | `realtime_factor` | 61.2x |", text)  # kept, though its JSON is gone
        self.assertIn("| e2e | `recording_cost` | 1.2 % |", text)
        self.assertRegex(text, r"\nThe e2e rows were rewritten alone: \d+ cores( of [^,]+, [a-z0-9]+)?, load average "
                               r"\d+\.\d over the last minute when they were written\.\n")
        self.assertEqual(run(TABLE, "--check", "--doc", doc).returncode, 0)
        # Again, with the load the benchmark measured: one line per benchmark; a whole rewrite drops it.
        (bench / "e2e.json").write_text(json.dumps({"loadavg": 11.04, "recording": {"recording_cost": 0.0123}}))
        self.assertEqual(run(TABLE, "--only", "e2e", "--bench-dir", bench, "--doc", doc).returncode, 0)
        self.assertEqual(doc.read_text().count("rows were rewritten alone"), 1)
        self.assertIn("load average 11.0 while they were measured.", doc.read_text())
        self.assertEqual(run(TABLE, "--check", "--doc", doc).returncode, 0)
        self.assertEqual(run(TABLE, "--bench-dir", bench, "--doc", doc).returncode, 0)
        self.assertNotIn("rewritten alone", doc.read_text())
        self.assertEqual(run(TABLE, "--only", "nothing", "--bench-dir", bench, "--doc", doc).returncode, 2)

    def test_a_partial_run_of_a_benchmark_keeps_its_rows_it_did_not_measure(self):
        doc, bench = self.document()
        (bench / "e2e.json").write_text(json.dumps({"realtime_factor": 10.5, "recording": {"recording_cost": 0.05}}))
        self.assertEqual(run(TABLE, "--bench-dir", bench, "--doc", doc).returncode, 0)
        # The recording rounds alone: their rows change, the whole run's realtime_factor stays.
        (bench / "e2e.json").write_text(json.dumps({"recording": {"recording_cost": 0.0123}}))
        self.assertEqual(run(TABLE, "--only", "e2e", "--bench-dir", bench, "--doc", doc).returncode, 0)
        text = doc.read_text()
        self.assertIn("| e2e | `realtime_factor` | 10.50x |", text)
        self.assertIn("| e2e | `recording_cost` | 1.2 % |", text)
        self.assertEqual(run(TABLE, "--check", "--doc", doc).returncode, 0)

    def test_a_missing_marker_fails(self):
        doc, _ = self.document()
        doc.write_text("# Benchmarks\n\n<!-- bench-table:begin -->\n")
        result = run(TABLE, "--check", "--doc", doc)
        self.assertEqual(result.returncode, 1)
        self.assertIn("bench-table:end", result.stderr)

    def test_the_descriptions_hold_no_cell_separator(self):
        sys.path.insert(0, str(TABLE.parent))
        import bench_table
        for row in bench_table.ROWS:
            self.assertNotIn("|", row.what + row.figure, row.figure)

    def test_the_machine_line_names_the_cpu_and_its_widest_vector_instructions(self):
        sys.path.insert(0, str(TABLE.parent))
        import bench_table
        with tempfile.TemporaryDirectory() as tmp:
            info = Path(tmp) / "cpuinfo"
            info.write_text("processor\t: 0\nmodel name\t: AMD EPYC\nflags\t\t: fpu sse2 avx avx2 fma\n\n"
                            "processor\t: 1\nmodel name\t: AMD EPYC\nflags\t\t: fpu sse2 avx avx2 fma\n")
            self.assertEqual(bench_table.cpu_name(str(info)), " of AMD EPYC, avx2")
            info.write_text("model name\t: Intel(R) Xeon(R) Platinum 8375C CPU @ 2.90GHz\n"
                            "flags\t\t: sse2 avx avx2 avx512f avx512dq\n")
            line = bench_table.MACHINE.format(cores=2, cpu=bench_table.cpu_name(str(info)), load="1.5")
            self.assertIn("2 cores of Intel(R) Xeon(R) Platinum 8375C CPU @ 2.90GHz, avx512, load", line)
            self.assertRegex(line, bench_table.MACHINE_LINE)
            # A table written before the CPU was named still reads.
            self.assertRegex(bench_table.MACHINE.format(cores=2, cpu="", load="1.5"), bench_table.MACHINE_LINE)
        self.assertEqual(bench_table.cpu_name("/nonexistent/cpuinfo"), "")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
