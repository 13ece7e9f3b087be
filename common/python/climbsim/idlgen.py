"""IDL -> Python type support for Cyclone DDS's Python binding, run at build time.

Cyclone's own `idlc -l py` needs an idlc of the same release as the Python package (the
PyPI wheel ships the plugin but no idlc; Debian's idlc 0.10 crashes on the 11.x plugin), so
climbsim compiles the subset of IDL that idl/*.idl uses itself: one module, `@final`
structs with `@key` members, enums, the primitive types, `string<N>`, `sequence<T, N>` and
fixed arrays `T name[N]`, in one module (which may be reopened). Anything else is an error naming the file and line, so a new IDL
feature cannot be silently dropped.

    python3 -m climbsim.idlgen --out DIR idl/clock.idl idl/thermo.idl ...

writes DIR/climbsim_idl.py: one dataclass per struct (type name "climbsim::Name", the same
name Fast DDS registers), one IdlEnum per enum, and IDL_HASHES, the SHA-256 of each file's
bytes (what idl/CMakeLists.txt puts into idl_hashes.hpp for the C++ participants).
"""

from __future__ import annotations

import argparse
import hashlib
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

PRIMITIVES = {
    "boolean": ("bool", "False"),
    "octet": ("types.uint8", "0"),
    "char": ("types.char", "'\\x00'"),
    "short": ("types.int16", "0"),
    "unsigned short": ("types.uint16", "0"),
    "long": ("types.int32", "0"),
    "unsigned long": ("types.uint32", "0"),
    "long long": ("types.int64", "0"),
    "unsigned long long": ("types.uint64", "0"),
    "float": ("types.float32", "0.0"),
    "double": ("types.float64", "0.0"),
}


#: Largest sequence bound Cyclone DDS Python encodes; larger bounds (images, test payloads)
#: become unbounded sequences, which XCDR1 serialises to the same bytes.
MAX_PY_SEQUENCE_BOUND = 65535


class IdlError(Exception):
    """A construct outside the supported subset, or a syntax error: names file and line."""


@dataclass
class Member:
    name: str
    type_text: str  # Python annotation
    default: str  # Python expression of the zero value
    key: bool
    idl_type: str  # the IDL type as written, normalised (for tests and error messages)
    array: int | None = None


@dataclass
class Struct:
    name: str
    final: bool
    members: list[Member] = field(default_factory=list)


@dataclass
class Enum:
    name: str
    values: list[str]


@dataclass
class IdlFile:
    path: Path
    module: str
    structs: list[Struct]
    enums: list[Enum]
    sha256: str


_TOKEN = re.compile(r"\s*(?:(@\w+)|([A-Za-z_]\w*)|(\d+)|(::|[^\s\w]))")


def _strip_comments(text: str) -> str:
    # Keep newlines so that line numbers in errors stay right.
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def _tokens(text: str, path: Path):
    pos = 0
    line = 1
    while True:
        while pos < len(text) and text[pos].isspace():
            line += text[pos] == "\n"
            pos += 1
        if pos >= len(text):
            return
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise IdlError(f"{path}:{line}: unexpected character {text[pos]!r}")
        tok = m.group(0).strip()
        line += m.group(0).count("\n")
        pos = m.end()
        yield tok, line


class _Parser:
    def __init__(self, path: Path, text: str):
        self.path = path
        self.toks = list(_tokens(_strip_comments(text), path))
        self.i = 0
        self.known_structs: set[str] = set()
        self.known_enums: set[str] = set()

    def error(self, message: str) -> IdlError:
        line = self.toks[min(self.i, len(self.toks) - 1)][1] if self.toks else 1
        return IdlError(f"{self.path}:{line}: {message}")

    def peek(self) -> str | None:
        return self.toks[self.i][0] if self.i < len(self.toks) else None

    def next(self) -> str:
        if self.i >= len(self.toks):
            raise self.error("unexpected end of file")
        tok = self.toks[self.i][0]
        self.i += 1
        return tok

    def expect(self, want: str) -> None:
        got = self.next()
        if got != want:
            self.i -= 1
            raise self.error(f"expected '{want}', found '{got}'")

    def number(self) -> int:
        tok = self.next()
        if not tok.isdigit():
            self.i -= 1
            raise self.error(f"expected a number, found '{tok}'")
        return int(tok)

    def parse(self) -> tuple[str, list[Struct], list[Enum]]:
        module = None
        structs: list[Struct] = []
        enums: list[Enum] = []
        while self.peek() is not None:
            self.expect("module")
            name = self.next()
            if module is not None and name != module:
                raise self.error(f"module '{name}' after module '{module}': one module name per file")
            module = name
            self.expect("{")
            self.module_body(structs, enums)
            self.expect("}")
            self.expect(";")
        if module is None:
            raise self.error("no module")
        return module, structs, enums

    def module_body(self, structs: list[Struct], enums: list[Enum]) -> None:
        while self.peek() != "}":
            annotations = []
            while self.peek() is not None and self.peek().startswith("@"):
                annotations.append(self.next())
            kind = self.next()
            if kind == "struct":
                for a in annotations:
                    if a != "@final":
                        raise self.error(f"annotation {a} on a struct is not supported (only @final)")
                structs.append(self.struct("@final" in annotations))
            elif kind == "enum":
                if annotations:
                    raise self.error(f"annotations {annotations} on an enum are not supported")
                enums.append(self.enum())
            else:
                self.i -= 1
                raise self.error(f"'{kind}' is not supported here (only struct and enum)")

    def enum(self) -> Enum:
        name = self.next()
        self.expect("{")
        values = []
        while True:
            values.append(self.next())
            tok = self.next()
            if tok == "}":
                break
            if tok != ",":
                self.i -= 1
                raise self.error(f"expected ',' or '}}' in enum {name}")
        self.expect(";")
        self.known_enums.add(name)
        return Enum(name, values)

    def type_spec(self) -> tuple[str, str, str]:
        """Returns (python annotation, python default, normalised IDL type)."""
        tok = self.next()
        if tok == "unsigned":
            tok += " " + self.next()
            if tok == "unsigned long" and self.peek() == "long":
                tok += " " + self.next()
        elif tok == "long" and self.peek() == "long":
            tok += " " + self.next()
        if tok in PRIMITIVES:
            py, default = PRIMITIVES[tok]
            return py, default, tok
        if tok == "string":
            if self.peek() != "<":
                return "str", "''", "string"
            self.expect("<")
            n = self.number()
            self.expect(">")
            return f"types.bounded_str[{n}]", "''", f"string<{n}>"
        if tok == "sequence":
            self.expect("<")
            py, _, idl = self.type_spec()
            bound = None
            if self.peek() == ",":
                self.next()
                bound = self.number()
            self.expect(">")
            if bound is None or bound > MAX_PY_SEQUENCE_BOUND:
                # Same bytes on the wire (length, then the elements); the bound is not checked.
                return f"types.sequence[{py}]", "list", f"sequence<{idl}>" if bound is None else f"sequence<{idl}, {bound}>"
            return f"types.sequence[{py}, {bound}]", "list", f"sequence<{idl}, {bound}>"
        if tok in self.known_structs:
            return tok, tok, tok
        if tok in self.known_enums:
            return tok, f"{tok}(0)", tok
        self.i -= 1
        raise self.error(f"type '{tok}' is not supported (or not declared before its use)")

    def struct(self, final: bool) -> Struct:
        s = Struct(self.next(), final)
        self.expect("{")
        while self.peek() != "}":
            key = False
            while self.peek() is not None and self.peek().startswith("@"):
                a = self.next()
                if a != "@key":
                    raise self.error(f"member annotation {a} is not supported (only @key)")
                key = True
            py, default, idl = self.type_spec()
            name = self.next()
            array = None
            if self.peek() == "[":
                self.next()
                array = self.number()
                self.expect("]")
                if self.peek() == "[":
                    raise self.error("multi-dimensional arrays are not supported")
                py = f"types.array[{py}, {array}]"
                idl = f"{idl}[{array}]"
            self.expect(";")
            s.members.append(Member(name, py, default, key, idl, array))
        self.expect("}")
        self.expect(";")
        self.known_structs.add(s.name)
        return s


def parse_file(path: Path, known_structs: set[str] | None = None, known_enums: set[str] | None = None) -> IdlFile:
    """Parses one IDL file of the supported subset; raises IdlError naming file and line."""
    data = path.read_bytes()
    parser = _Parser(path, data.decode("utf-8"))
    parser.known_structs |= known_structs or set()
    parser.known_enums |= known_enums or set()
    module, structs, enums = parser.parse()
    return IdlFile(path, module, structs, enums, hashlib.sha256(data).hexdigest())


def parse_files(paths: list[Path]) -> list[IdlFile]:
    files: list[IdlFile] = []
    structs: set[str] = set()
    enums: set[str] = set()
    for p in paths:
        f = parse_file(p, structs, enums)
        structs |= {s.name for s in f.structs}
        enums |= {e.name for e in f.enums}
        files.append(f)
    return files


def _default_expr(m: Member) -> str:
    if m.array is not None:
        base = m.default
        if base in ("list",):
            return f"field(default_factory=lambda: [[] for _ in range({m.array})])"
        if base and base[0].isupper() and "(" not in base:
            return f"field(default_factory=lambda: [{base}() for _ in range({m.array})])"
        return f"field(default_factory=lambda: [{base}] * {m.array})"
    if m.default == "list":
        return "field(default_factory=list)"
    if m.default and m.default[0].isupper() and "(" not in m.default and m.default not in ("False", "True"):
        return f"field(default_factory={m.default})"  # a nested struct
    return m.default


def generate(files: list[IdlFile]) -> str:
    """The Python source of the climbsim_idl module for these files."""
    out = [
        '"""climbsim message types for Cyclone DDS Python, generated by climbsim.idlgen from',
        "idl/*.idl at build time; do not edit, do not commit.",
        '"""',
        "",
        "from dataclasses import dataclass, field",
        "",
        "from cyclonedds.idl import IdlEnum, IdlStruct",
        "from cyclonedds.idl import annotations as annotate",
        "from cyclonedds.idl import types",
        "",
        "#: SHA-256 of every IDL file these types were generated from: (file name, hex digest),",
        "#: announced in ParticipantReady so that the clock can refuse mismatched builds.",
        "IDL_HASHES = (",
    ]
    out += [f"    ({f.path.name!r}, {f.sha256!r})," for f in files]
    out += [")", ""]
    for f in files:
        out.append(f"# ---- {f.path.name}")
        for e in f.enums:
            out += ["", "", f"class {e.name}(IdlEnum, typename={f.module + '::' + e.name!r}):"]
            out += [f"    {v} = {i}" for i, v in enumerate(e.values)]
        for s in f.structs:
            keys = [m.name for m in s.members if m.key]
            out += ["", "", "@dataclass"]
            if s.final:
                out.append("@annotate.final")
            if keys:
                out.append("@annotate.keylist([" + ", ".join(repr(k) for k in keys) + "])")
            out.append(f"class {s.name}(IdlStruct, typename={f.module + '::' + s.name!r}):")
            for m in s.members:
                out.append(f"    {m.name}: {m.type_text} = {_default_expr(m)}")
            if not s.members:
                out.append("    pass")
        out.append("")
    names = [s.name for f in files for s in f.structs] + [e.name for f in files for e in f.enums]
    out += ["", "__all__ = ['IDL_HASHES', " + ", ".join(repr(n) for n in names) + "]", ""]
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, type=Path, help="directory for climbsim_idl.py")
    ap.add_argument("idl", nargs="+", type=Path)
    args = ap.parse_args(argv)
    try:
        files = parse_files(args.idl)
    except (IdlError, OSError, UnicodeDecodeError) as e:
        print(f"climbsim.idlgen: error: {e}", file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    target = args.out / "climbsim_idl.py"
    text = generate(files)
    # Rewrite only on change so that dependent build steps stay up to date.
    if not target.exists() or target.read_text() != text:
        target.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
