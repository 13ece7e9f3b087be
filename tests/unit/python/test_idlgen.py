"""climbsim.idlgen against the real idl/ files: the generated types are what the IDL says, so
the Python types cannot drift from the C++ ones (both are generated from idl/ at build time)."""

import hashlib
import importlib.util
import os
import re
import sys
import tempfile
import unittest
from pathlib import Path

from climbsim import idlgen

ROOT = Path(os.environ.get("CLIMBSIM_ROOT", Path(__file__).resolve().parents[3]))
IDL_FILES = sorted((ROOT / "idl").glob("*.idl"))


def load_generated(out_dir: Path):
    spec = importlib.util.spec_from_file_location("climbsim_idl_under_test", out_dir / "climbsim_idl.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


class GeneratedTypes(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        assert idlgen.main(["--out", cls.tmp.name, *map(str, IDL_FILES)]) == 0
        cls.mod = load_generated(Path(cls.tmp.name))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_struct_of_every_file_with_its_members_in_order(self):
        self.assertGreaterEqual(len(IDL_FILES), 6)
        for path in IDL_FILES:
            text = re.sub(r"//[^\n]*", "", path.read_text())
            for name, body in re.findall(r"struct\s+(\w+)\s*\{(.*?)\};", text, flags=re.S):
                cls = getattr(self.mod, name)
                self.assertEqual(cls.__idl_typename__, f"climbsim::{name}")
                members = [m.split()[-1].split("[")[0] for m in body.split(";") if m.strip()]
                self.assertEqual(list(cls.__annotations__), members, f"{path.name}: {name}")
                keys = [m.split()[-1] for m in body.split(";") if "@key" in m]
                self.assertEqual(cls.__idl_annotations__.get("keylist", []), keys, f"{path.name}: {name} keys")
                self.assertEqual(cls.__idl_annotations__.get("extensibility"), "final", f"{path.name}: {name}")

    def test_hashes_are_the_sha256_of_the_files_bytes(self):
        expected = tuple((p.name, hashlib.sha256(p.read_bytes()).hexdigest()) for p in IDL_FILES)
        self.assertEqual(self.mod.IDL_HASHES, expected)

    def test_xcdr1_layout_of_a_keyed_sample_is_plain_cdr(self):
        # Fast DDS 2.9 reads XCDR1: 8-byte members aligned to 8 after the 4-byte header.
        sample = self.mod.AdhesionForce(source="x", step=3, t_ns=-1, downforce_n=1.0)
        data = sample.serialize(use_version_2=False)
        self.assertEqual(data[:4], bytes([0, 1, 0, 0]))  # CDR_LE
        self.assertEqual(data[4:10], bytes([2, 0, 0, 0]) + b"x\0")
        self.assertEqual(data[12:20], (3).to_bytes(8, "little"))
        self.assertEqual(self.mod.AdhesionForce.deserialize(data), sample)

    def test_arrays_and_sequences_default_to_their_idl_shape(self):
        state = self.mod.ChamberState()
        self.assertEqual(state.pressure_pa, [])
        self.assertEqual(state.engine_speed, [])
        self.assertEqual(len(self.mod.RobotState().position_m), 3)
        self.assertEqual(self.mod.StepDone().kind, self.mod.StepDoneKind.STEP_DONE)


class UnsupportedIdl(unittest.TestCase):
    def compile(self, text: str) -> str:
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "bad.idl"
            path.write_text(text)
            with self.assertRaises(idlgen.IdlError) as caught:
                idlgen.parse_files([path])
            return str(caught.exception)

    def test_a_union_is_refused_with_file_and_line(self):
        message = self.compile("module climbsim {\n  @final\n  union U switch (long) { case 1: long a; };\n};\n")
        self.assertRegex(message, r"bad\.idl:3: .*union")

    def test_an_unknown_member_type_is_refused(self):
        message = self.compile("module climbsim {\n  struct S {\n    wstring w;\n  };\n};\n")
        self.assertRegex(message, r"bad\.idl:3: type 'wstring' is not supported")

    def test_an_unknown_annotation_is_refused(self):
        message = self.compile("module climbsim {\n  @appendable\n  struct S { long a; };\n};\n")
        self.assertIn("@appendable", message)


if __name__ == "__main__":
    unittest.main()
