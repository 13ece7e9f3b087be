#!/usr/bin/env python3
"""The reference checker: every reference to a document of docs/, to a heading of README.md and
to a Markdown file of the repository resolves.

It scans every file of the repository (`git ls-files`: tracked and untracked-but-not-ignored
files; without git, a walk that leaves out build*/, .git/ and node_modules/) and fails when

- a reference `docs/<name>.md` or `docs/<name>.md#<anchor>` (in any file: code, comments, CMake,
  scripts, documents) names a document that does not exist, or a heading anchor that the
  document does not have;
- a Markdown link in README.md or docs/*.md (`[text](<name>.md#<anchor>)`, `[text](#<anchor>)`,
  `[text](../<name>.md)`, ...) names a file that does not exist, or an anchor its target lacks;
- a citation of a README.md heading by name, `README "<heading>"`, `README.md, "<heading>"` or
  `README's "<heading>"` (the quoted name may wrap onto the next comment line), names a heading
  README.md does not have (compared by anchor, so case and punctuation do not matter; a name in
  angle brackets is a placeholder);
- a path of a Markdown file, `<path>.md` or `<path>.md#<anchor>` (`services/<name>/README.md`,
  `<NAME>.md`), names a file that exists neither from the repository's top folder nor from the
  citing file's folder, or an anchor the file lacks. A name right inside quotes ("x.md") is a
  file name a program builds, not a reference, and a path that follows a variable (`$ROOT/x.md`,
  `{folder}x.md`) cannot be checked: both are left alone;
- a file mentions the design document that lived outside the repository (its name is built
  below, so that this file does not mention it).

Anchors follow GitHub's rules: the heading's text (links reduced to their text, inline code to
its content), lower case, every character that is not a letter, digit, space, '-' or '_'
dropped, each space turned into '-'; a heading whose anchor came before gets '-1', '-2', ...
An HTML anchor (`<a name="x">`, `<a id="x">`) counts as well.

Each finding is one line `FILE:LINE: reference 'REF': why`; the exit code is 1 when there is
one, 0 otherwise, 2 for bad arguments.

    python3 docs/tools/check_references.py [--root DIR]
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

# The outside design document's name, assembled so that this file is no mention of it.
OUTSIDE_DESIGN = "DESIGN" + ".md"

# docs/<name>.md[#ANCHOR] anywhere; not part of a longer path (services/x/docs/...).
DOCS_REFERENCE = re.compile(r"(?<![\w./-])docs/([\w.-]+?\.md)(?:#([\w-]*))?")
# A Markdown link or image target: ](target) or ](target "title").
MARKDOWN_LINK = re.compile(r"\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
# README "<heading>", README.md, "<heading>", README's "<heading>"; the name may wrap once, onto a
# line that starts with a comment leader.
README_CITATION = re.compile(r"\bREADME(?:\.md)?(?:'s)?,?[ \t]+\"([^\"\n]+(?:\n[^\"\n]*)?)\"")
COMMENT_CONTINUATION = re.compile(r"[ \t]*\n[ \t]*(?:#+|//+|/?\*+|--|;+)?[ \t]*")
# A Markdown file's path anywhere, with an optional anchor; not the tail of a longer path or URL,
# nor a path that follows a variable ($X/, {x}, ~/).
MARKDOWN_PATH = re.compile(r"(?<![\w./*${}~>-])((?:\.\.?/)*(?:[\w.-]+/)*[\w-][\w.-]*\.md)(?:#([\w-]*))?(?![\w/])")
HTML_ANCHOR = re.compile(r"<a\s+(?:name|id)\s*=\s*\"([^\"]+)\"", re.IGNORECASE)
ATX_HEADING = re.compile(r"^ {0,3}(#{1,6})(?:[ \t]+(.*?))?[ \t]*$")
FENCE = re.compile(r"^ {0,3}(```+|~~~+)")
SETEXT_UNDERLINE = re.compile(r"^ {0,3}(=+|-+)[ \t]*$")

SKIPPED_DIRS = {".git", "node_modules"}


def github_anchor(heading: str) -> str:
    """The anchor GitHub gives a heading's text (before duplicates are numbered)."""
    text = heading.strip()
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links and images: their text
    text = re.sub(r"<[^>]+>", "", text)                      # inline HTML
    text = text.replace("`", "")                             # inline code: its content
    text = text.lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def strip_closing_hashes(text: str) -> str:
    """An ATX heading's optional closing sequence of '#' goes."""
    return re.sub(r"(?:^|[ \t]+)#+[ \t]*$", "", text).strip()


def anchors_of(markdown: str) -> set[str]:
    """Every anchor a Markdown text offers: its headings' (numbered as GitHub numbers
    duplicates) and its HTML anchors. Headings inside fenced code blocks do not count."""
    seen: dict[str, int] = {}
    anchors: set[str] = set()

    def add(heading_text: str) -> None:
        base = github_anchor(heading_text)
        if not base:
            return
        count = seen.get(base, 0)
        seen[base] = count + 1
        anchors.add(base if count == 0 else f"{base}-{count}")

    fence: str | None = None
    previous: str | None = None  # the previous line, if it could be a setext heading's text
    for line in markdown.splitlines():
        opening = FENCE.match(line)
        if fence is not None:
            if opening and opening.group(1)[0] == fence[0] and len(opening.group(1)) >= len(fence):
                fence = None
            previous = None
            continue
        if opening:
            fence = opening.group(1)
            previous = None
            continue
        anchors.update(HTML_ANCHOR.findall(line))
        atx = ATX_HEADING.match(line)
        if atx:
            add(strip_closing_hashes(atx.group(2) or ""))
            previous = None
            continue
        if previous is not None and SETEXT_UNDERLINE.match(line) and previous.strip():
            add(previous)
            previous = None
            continue
        plain = line.strip() and not line.startswith(("    ", "\t")) and not re.match(r"^ {0,3}([-*+>|]|\d+[.)])", line)
        previous = line if plain else None
    return anchors


class Repository:
    """The files of a checkout and the anchors of its Markdown documents (read once each)."""

    def __init__(self, root: Path):
        self.root = root
        self._anchors: dict[Path, set[str]] = {}

    def files(self) -> list[Path]:
        """Relative paths of every file to scan, sorted."""
        if (self.root / ".git").exists():
            listed = subprocess.run(
                ["git", "-C", str(self.root), "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                check=True, capture_output=True).stdout.decode("utf-8", "surrogateescape")
            paths = {Path(p) for p in listed.split("\0") if p}
            return sorted(p for p in paths if (self.root / p).is_file())
        found = []
        for folder, dirs, names in os.walk(self.root):
            dirs[:] = sorted(d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build"))
            for name in names:
                found.append((Path(folder) / name).relative_to(self.root))
        return sorted(found)

    def anchors(self, document: Path) -> set[str]:
        if document not in self._anchors:
            self._anchors[document] = anchors_of(document.read_text(encoding="utf-8", errors="replace"))
        return self._anchors[document]


def read_text(path: Path) -> str | None:
    """The file's text, or None for a binary file."""
    data = path.read_bytes()
    if b"\0" in data[:8192]:
        return None
    return data.decode("utf-8", errors="replace")


def is_guide_document(relative: Path) -> bool:
    """README.md at the top and every docs/*.md: their Markdown links are checked too."""
    parts = relative.parts
    return parts == ("README.md",) or (len(parts) == 2 and parts[0] == "docs" and relative.suffix == ".md")


def check_target(repo: Repository, document: Path, anchor: str | None) -> str | None:
    """Why `document` (absolute) with `anchor` does not resolve, or None."""
    if not document.is_file():
        return "no such document"
    if anchor and document.suffix == ".md" and anchor not in repo.anchors(document):
        return f"no heading with the anchor '{anchor}' in {document.relative_to(repo.root).as_posix()}"
    return None


def readme_citation_findings(repo: Repository, relative: Path, text: str) -> list[str]:
    """Citations of README.md headings by name that name no heading of README.md."""
    findings = []
    readme = repo.root / "README.md"
    for match in README_CITATION.finditer(text):
        heading = COMMENT_CONTINUATION.sub(" ", match.group(1)).strip()
        if heading.startswith("<") and heading.endswith(">"):
            continue  # a placeholder
        if readme.is_file() and github_anchor(heading) in repo.anchors(readme):
            continue
        number = text.count("\n", 0, match.start()) + 1
        why = f"no heading '{heading}' in README.md" if readme.is_file() else "no README.md"
        findings.append(f"{relative.as_posix()}:{number}: reference 'README \"{heading}\"': {why}")
    return findings


def markdown_path_why(repo: Repository, relative: Path, name: str, anchor: str | None) -> str | None:
    """Why the Markdown file `name` (from the top folder or from `relative`'s folder) with
    `anchor` does not resolve, or None."""
    root = repo.root.resolve()
    why = "no such file"
    for base in (root, (root / relative).parent):
        document = (base / name).resolve()
        try:
            document.relative_to(root)
        except ValueError:
            continue
        if document.is_file():
            found = check_target(repo, document, anchor)
            if found is None:
                return None
            why = found
    return why


def markdown_path_findings(repo: Repository, relative: Path, line: str, where: str,
                           skipped: list[tuple[int, int]]) -> list[str]:
    """Paths of Markdown files on one line that do not resolve; spans in `skipped` (links the
    guide documents' own rule checks) are left out."""
    findings = []
    for match in MARKDOWN_PATH.finditer(line):
        name, anchor = match.group(1), match.group(2) or None
        start, end = match.span()
        if any(a <= start < b for a, b in skipped):
            continue
        before, after = line[start - 1:start], line[end:end + 1]
        if before in ("\"", "'") and after == before:
            continue  # a file name in a string literal
        if name.startswith("docs/") or Path(name).name == OUTSIDE_DESIGN:
            continue  # the rules of docs/ and of the outside design document say it
        why = markdown_path_why(repo, relative, name, anchor)
        if why:
            findings.append(f"{where}: reference '{match.group(0)}': {why}")
    return findings


def check_file(repo: Repository, relative: Path) -> list[str]:
    """The findings of one file."""
    path = repo.root / relative
    text = read_text(path)
    if text is None:
        return []
    findings = readme_citation_findings(repo, relative, text)
    guide = is_guide_document(relative)
    fence: str | None = None
    for number, line in enumerate(text.splitlines(), start=1):
        where = f"{relative.as_posix()}:{number}"
        if OUTSIDE_DESIGN in line:
            findings.append(f"{where}: reference '{OUTSIDE_DESIGN}': the design is docs/design.md; "
                            "cite a docs/ file and heading instead")
        for match in DOCS_REFERENCE.finditer(line):
            anchor = match.group(2) or None
            why = check_target(repo, repo.root / "docs" / match.group(1), anchor)
            if why:
                findings.append(f"{where}: reference '{match.group(0)}': {why}")
        if not guide:
            findings.extend(markdown_path_findings(repo, relative, line, where, []))
            continue
        opening = FENCE.match(line)
        if fence is not None:
            if opening and opening.group(1)[0] == fence[0] and len(opening.group(1)) >= len(fence):
                fence = None
            continue
        if opening:
            fence = opening.group(1)
            continue
        links = [match.span(1) for match in MARKDOWN_LINK.finditer(line)]
        findings.extend(markdown_path_findings(repo, relative, line, where, links))
        for match in MARKDOWN_LINK.finditer(line):
            target = match.group(1)
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("//"):
                continue  # a URL (https:, mailto:, ...)
            name, _, anchor = target.partition("#")
            document = path if not name else (path.parent / name).resolve()
            try:
                document.relative_to(repo.root.resolve())
            except ValueError:
                findings.append(f"{where}: reference '{target}': it leaves the repository")
                continue
            if not name or name.endswith(".md"):
                why = check_target(repo, document, anchor or None)
            else:
                why = None if document.exists() else "no such file"
            if why:
                findings.append(f"{where}: reference '{target}': {why}")
    prefix = len(relative.as_posix()) + 1
    return sorted(findings, key=lambda finding: int(finding[prefix:].split(":", 1)[0]))


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(
        description="Fail on references to docs/, to README.md's headings and to Markdown files that do not resolve.")
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parents[2],
                        help="the repository's top folder (default: this checkout)")
    args = parser.parse_args(argv)
    root = args.root.resolve()
    if not root.is_dir():
        print(f"check_references: --root = '{args.root}': not a folder", file=sys.stderr)
        return 2
    repo = Repository(root)
    findings = []
    files = repo.files()
    for relative in files:
        findings.extend(check_file(repo, relative))
    for finding in findings:
        print(finding)
    if findings:
        print(f"check_references: {len(findings)} reference(s) that do not resolve, in {len(files)} files",
              file=sys.stderr)
        return 1
    print(f"check_references: every reference resolves ({len(files)} files)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
