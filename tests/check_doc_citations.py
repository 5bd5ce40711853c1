#!/usr/bin/python3
"""Every document a tracked file cites is in the repository.

usage: check_doc_citations.py [SOURCE_DIR]

The repository's comments and docs cite `docs/*.md` sections; a clone must be
able to open what they cite. The check fails (exit 1, one line per problem,
"path:line: what") on
  - a citation of the design, problem and style notes that were kept outside
    the repository (their names and the sibling folder they lived in, see
    FORBIDDEN below);
  - a markdown link `[text](target)` in a `.md` file whose target file is not
    in the repository, or whose `#anchor` is neither a heading of the target
    (GitHub's anchor rule) nor an explicit `<a id=...>` in it;
  - a mention of `docs/NAME.md` (any file) that does not exist;
  - a section citation `NAME.md §N` (or `§N-M`, `§N, §M`) whose file has no
    heading numbered N, and a bare `§N` in a `docs/*.md` file that its own
    file lacks.
The files are those of `git ls-files` when SOURCE_DIR is a git checkout,
else every file under SOURCE_DIR outside hidden, build and output folders.
"""
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                       os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

# Built from pieces so that this file does not cite them itself.
FORBIDDEN = [
    ("the design notes", re.compile(r"\b" + "DES" + r"IGN\b")),
    ("the problem notes", re.compile("PROB" + r"LEMS\.md")),
    ("the style notes", re.compile("STY" + r"LE(?: §|\.md)")),
    ("the folder beside the repository", re.compile(r"\.\./" + "sha" + "red")),
]
LINK = re.compile(r"!?\[([^\]\n]*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
DOCS_PATH = re.compile(r"(?<![\w./-])(docs/[\w./-]*?\.md)\b")
SECTION_CITE = re.compile(r"(?<![\w./-])((?:docs/)?[\w-]+\.md)\)?\s*§\s*([A-Z]?\d+[a-z]?(?:\.\d+)*)"
                          r"((?:\s*(?:-|–|,\s*§|and\s+§)\s*[A-Z]?\d+[a-z]?(?:\.\d+)*)*)")
BARE_SECTION = re.compile(r"(?<![\w.])§\s*([A-Z]?\d+[a-z]?(?:\.\d+)*)"
                          r"((?:\s*(?:-|–|,\s*§|and\s+§)\s*[A-Z]?\d+[a-z]?(?:\.\d+)*)*)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
HEADING_NUMBER = re.compile(r"^([A-Z]?\d+[a-z]?(?:\.\d+)*)\.?(?:\s|$)")
EXPLICIT_ANCHOR = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
SKIP_DIRS = {".git", "out", "runs", "stage", "device-report", "__pycache__"}


def tracked_files():
    try:
        out = subprocess.run(["git", "-C", ROOT, "ls-files", "-z"], capture_output=True,
                             check=True).stdout.decode()
        files = [f for f in out.split("\0") if f]
        if files:
            return files, "git ls-files"
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for top, dirs, names in os.walk(ROOT):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in SKIP_DIRS
                         and not d.startswith("build") and not d.startswith("out"))
        for name in sorted(names):
            files.append(os.path.relpath(os.path.join(top, name), ROOT).replace(os.sep, "/"))
    return files, "the source tree (no git checkout)"


def read_text(rel):
    try:
        with open(os.path.join(ROOT, rel), "rb") as f:
            data = f.read()
    except OSError:
        return None
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def slug(text):
    """GitHub's anchor of a heading: markup dropped, lower case, punctuation
    removed, spaces to hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links keep their text
    text = re.sub(r"<[^>]+>", "", text)
    text = text.lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


class Document:
    """Headings, anchors and section numbers of one markdown file."""

    def __init__(self, text):
        self.anchors, self.sections = set(), set()
        counts = {}
        fence = False
        for line in text.splitlines():
            if line.lstrip().startswith("```"):
                fence = not fence
                continue
            if fence:
                continue
            for anchor in EXPLICIT_ANCHOR.findall(line):
                self.anchors.add(anchor)
            m = HEADING.match(line)
            if not m:
                continue
            title = m.group(2)
            base = slug(title)
            n = counts.get(base, 0)
            counts[base] = n + 1
            self.anchors.add(base if n == 0 else f"{base}-{n}")
            num = HEADING_NUMBER.match(title)
            if num:
                self.sections.add(num.group(1))


def section_numbers(first, rest):
    nums = [first]
    nums += re.findall(r"[A-Z]?\d+[a-z]?(?:\.\d+)*", rest or "")
    return nums


def section_exists(doc, num):
    # "§4" needs a heading numbered "4." and "§4.2" one numbered "4.2"; both
    # ends of a range ("§4.2-4.4") must exist.
    return num in doc.sections


def main():
    files, source = tracked_files()
    file_set = set(files)
    docs_cache = {}
    problems = []

    def document(rel):
        if rel not in docs_cache:
            text = read_text(rel)
            docs_cache[rel] = Document(text) if text is not None else None
        return docs_cache[rel]

    def exists(rel):
        rel = os.path.normpath(rel).replace(os.sep, "/")
        return rel in file_set or os.path.isfile(os.path.join(ROOT, rel))

    this_file = os.path.relpath(os.path.abspath(__file__), ROOT).replace(os.sep, "/")
    for rel in files:
        if rel == this_file:
            continue
        text = read_text(rel)
        if text is None:
            continue
        is_md = rel.endswith(".md")
        here = os.path.dirname(rel)
        fence = False
        for lineno, line in enumerate(text.splitlines(), 1):
            where = f"{rel}:{lineno}"
            for what, pattern in FORBIDDEN:
                if pattern.search(line):
                    problems.append(f"{where}: cites {what}, which the repository does not hold: "
                                    f"{line.strip()[:120]}")
            for m in DOCS_PATH.finditer(line):
                if not exists(m.group(1)):
                    problems.append(f"{where}: mentions {m.group(1)}, which is not in the repository")
            for m in SECTION_CITE.finditer(line):
                name = m.group(1)
                target = name if name.startswith("docs/") else None
                if target is None:
                    for candidate in (os.path.join(here, name), os.path.join("docs", name), name):
                        if exists(candidate):
                            target = os.path.normpath(candidate).replace(os.sep, "/")
                            break
                if target is None or not exists(target):
                    continue  # reported as a missing file above, or not a repository file
                doc = document(target)
                if doc is None:
                    continue
                for num in section_numbers(m.group(2), m.group(3)):
                    if not section_exists(doc, num):
                        problems.append(f"{where}: cites {name} §{num}, which has no such section")
            if not is_md:
                continue
            if line.lstrip().startswith("```"):
                fence = not fence
                continue
            if fence:
                continue
            for m in LINK.finditer(line):
                label, target = m.group(1), m.group(2)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                    continue  # a URL scheme (none should be a web host; not checked here)
                path, _, anchor = target.partition("#")
                resolved = rel if not path else os.path.normpath(os.path.join(here, path)).replace(os.sep, "/")
                if path and not exists(resolved):
                    problems.append(f"{where}: links to {target}, whose file is not in the repository")
                    continue
                if not resolved.endswith(".md"):
                    continue
                doc = document(resolved)
                if doc is None:
                    continue
                if anchor and anchor not in doc.anchors:
                    problems.append(f"{where}: links to {target}, which has no heading or "
                                    f"anchor '{anchor}'")
                for sm in BARE_SECTION.finditer(label):  # "[§5.2](method.md#...)"
                    for num in section_numbers(sm.group(1), sm.group(2)):
                        if not section_exists(doc, num):
                            problems.append(f"{where}: cites {resolved} §{num}, which has no such section")
            # A bare "§N" in a doc cites its own file (others are named, or linked).
            if rel.startswith("docs/"):
                stripped = LINK.sub("", line)
                stripped = SECTION_CITE.sub("", stripped)
                for m in BARE_SECTION.finditer(stripped):
                    doc = document(rel)
                    for num in section_numbers(m.group(1), m.group(2)):
                        if not section_exists(doc, num):
                            problems.append(f"{where}: cites §{num}, which {rel} does not have")

    if problems:
        print("\n".join(problems))
        print(f"{len(problems)} citation(s) that the repository cannot resolve "
              f"({len(files)} files from {source})")
        return 1
    print(f"every citation resolves ({len(files)} files from {source})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
