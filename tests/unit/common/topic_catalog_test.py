"""The topic table (`climbsim topics`, common/include/climbsim/topic_catalog.hpp) against the code:
every topic a service writes is in it with the type it writes, every name is a constant of
topic_names.hpp (the one header of C++ topic names), the Python and C lists generated from it
are the same table, every type is an IDL struct,
every QoS profile is in deploy/qos/climbsim.xml, and docs/design.md shows the table as printed.

    python3 topic_catalog_test.py ROOT CLIMBSIM_COMPOSE
"""

import re
import subprocess
import sys
import unittest
from pathlib import Path

ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[3]
COMPOSE = sys.argv[2] if len(sys.argv) > 2 else str(ROOT / "build" / "bin" / "climbsim-compose")


def constants(path: Path) -> dict[str, str]:
    """kName -> "topic/name" of a topic header."""
    return dict(re.findall(r'inline constexpr const char\* (k\w+) = "([^"]+)"', path.read_text()))


class TopicCatalog(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        out = subprocess.run([COMPOSE, "--root", str(ROOT), "--build", "/nonexistent", "topics"],
                             check=True, capture_output=True, text=True).stdout
        cls.table = out
        cls.rows = {}
        for line in out.splitlines()[2:]:
            cells = [c.strip().strip("`") for c in line.strip("|").split("|")]
            cls.rows[cells[0]] = {"type": cells[1].removeprefix("climbsim::"), "producer": cells[2],
                                  "rate": cells[3], "qos": cells[4]}
        include = ROOT / "common" / "include" / "climbsim"
        cls.names = constants(include / "topic_names.hpp")

    def test_every_topic_constant_is_in_the_table_and_nothing_else(self):
        self.assertEqual(set(self.rows), set(self.names.values()))

    def test_one_header_of_topic_names(self):
        # Every C++ topic constant is in topic_names.hpp: no other header declares one.
        topic = re.compile(r"(?:clock|controller|drive|scene|sealing|thermo|record)/[A-Z]\w+")
        headers = list((ROOT / "common" / "include").rglob("*.hpp")) + list((ROOT / "services").rglob("*.hpp"))
        others = [h.name for h in headers if h.name != "topic_names.hpp"
                  and any(topic.fullmatch(v) for v in constants(h).values())]
        self.assertEqual(others, [])

    def test_the_generated_python_and_c_lists_are_the_table(self):
        # climbsim-topicgen writes them into the build directory from topic_catalog.hpp.
        build = Path(COMPOSE).resolve().parents[1]
        py = (build / "python" / "climbsim_topics.py").read_text()
        self.assertEqual(set(re.findall(r'^[A-Z_]+ = "([^"]+)"', py, re.M)), set(self.rows))
        h = (build / "generated" / "topics" / "climbsim_topics.h").read_text()
        self.assertEqual(set(re.findall(r'^#define CLIMBSIM_TOPIC_\w+ "([^"]+)"', h, re.M)), set(self.rows))
        # Python's TOPICS rows are the table's rows, in its order.
        rows = re.findall(r'^    \("([^"]+)", "(\w+)"', py, re.M)
        self.assertEqual([name for name, _ in rows], list(self.rows))
        self.assertEqual({name: t for name, t in rows}, {name: r["type"] for name, r in self.rows.items()})

    def test_no_topic_list_of_its_own_in_python_or_c(self):
        # The committed sources take every topic name from the generated lists.
        topic = r'"((?:clock|controller|drive|scene|sealing|thermo|record)/[A-Z]\w+)"'
        self.assertEqual(re.findall(topic, (ROOT / "common/python/climbsim/topics.py").read_text()), [])
        c_dir = ROOT / "services/controller/examples/c"
        uses = set()
        for source in list(c_dir.glob("*.c")) + list(c_dir.glob("*.h")):
            text = source.read_text()
            self.assertEqual(re.findall(topic, text), [], source.name)
            uses |= set(re.findall(r"CLIMBSIM_TOPIC_(\w+)", text))
        self.assertGreaterEqual(len(uses), 5, uses)

    def test_every_type_is_an_idl_struct_and_every_profile_is_in_the_qos_file(self):
        structs = set()
        for idl in (ROOT / "idl").glob("*.idl"):
            structs |= set(re.findall(r"struct (\w+)", idl.read_text()))
        profiles = set(re.findall(r'profile_name="([^"]+?)(?:\.writer|\.reader)?"',
                                  (ROOT / "deploy/qos/climbsim.xml").read_text()))
        for topic, row in self.rows.items():
            self.assertIn(row["type"], structs, topic)
            self.assertIn(row["qos"], profiles, topic)

    def test_every_topic_a_service_writes_is_listed_with_its_type(self):
        names = self.names
        written = []
        for source in (ROOT / "services").glob("**/*.cpp"):
            text = source.read_text()
            for type_name, constant in re.findall(r"output<(\w+)PubSubType>\([\w:]*?(k\w+)\)", text):
                written.append((source, type_name, constant))
            for type_name, constant in re.findall(
                    r"Writer<(?:climbsim::)?(\w+)PubSubType>>?\(\s*[\w.()]+,\s*[\w:]*?(k\w+)", text, re.S):
                written.append((source, type_name, constant))
        self.assertGreaterEqual(len(written), 12, written)
        for source, type_name, constant in written:
            if constant not in names:
                continue  # a service's own alias of a constant (e.g. scene::topic::kDepthImage)
            self.assertIn(names[constant], self.rows, f"{source.name}: {constant}")
            self.assertEqual(self.rows[names[constant]]["type"], type_name, f"{source.name}: {constant}")

    def test_the_design_document_shows_the_table_as_printed(self):
        self.assertIn(self.table, (ROOT / "docs" / "design.md").read_text())


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
