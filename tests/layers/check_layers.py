#!/usr/bin/python3
"""The layer rules of PBMS, checked on the source tree (docs/architecture.md).

Usage: check_layers.py ROOT

Layers, lowest first: core, grid, coupling; then the drivers (md_driver,
dpd_driver, mpm_driver) and the coupler, each above coupling and beside the
others. Every quoted #include of a file under ROOT is resolved as the
compiler would (the including file's folder, then the include roots) and
must point into the file's own layer or one below it:
  - a driver includes no other driver's header;
  - the coupler includes no driver header;
  - grid/ includes nothing of coupling/, a driver or the coupler;
  - core/ includes nothing above it.
Stage and engine code (stage/ and engine/ folders, md_driver's stages, the
coupler's stages and fit) reads a parameter by string key, node["key"], only
inside its typed struct's reading function (a function whose name ends in
from_yaml) or a validation check (a name starting with check).
Exit 1 with one line per violation, naming file and line.
"""
import re
import sys
from pathlib import Path

LAYERS = {
    "core": {"core"},
    "grid": {"core", "grid"},
    "coupling": {"core", "grid", "coupling"},
    "md_driver": {"core", "grid", "coupling", "md_driver"},
    "dpd_driver": {"core", "grid", "coupling", "dpd_driver"},
    "mpm_driver": {"core", "grid", "coupling", "mpm_driver"},
    "coupler": {"core", "grid", "coupling", "coupler"},
}
INCLUDE_ROOTS = {
    "core": ["core/include"],
    "grid": ["grid/include"],
    "coupling": ["coupling/include"],
    "md_driver": ["md_driver"],
    "dpd_driver": ["dpd_driver"],
    "mpm_driver": ["mpm_driver"],
    "coupler": ["coupler"],
}
SOURCE = re.compile(r"\.(cpp|hpp|h)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
# node["key"], not followed by an assignment (building a request's map).
KEYED_READ = re.compile(r'[\w)\]]\s*\[\s*"[A-Za-z_][A-Za-z0-9_]*"\s*\](?!\s*=[^=])')
# What makes a subscript a write into a results map rather than a read.
RESULT_WRITE = re.compile(r'(attributes|\.scalars|\.columns)\s*\[\s*"[^"]*"\s*\]'
                          r'|\[\s*"[^"]*"\s*\]\s*\.push_back\(')
FUNCTION_START = re.compile(r"^[A-Za-z_][\w:<>,\s\*&]*?\b([A-Za-z_]\w*)\s*\(")
NOT_FUNCTION = re.compile(r"^(namespace|using|class|struct|enum|template|typedef|extern|static_assert)\b")


def layer_of(rel):
    top = rel.parts[0]
    return top if top in LAYERS else None


def resolve(root, including, name):
    """The file an #include "name" in `including` reaches, or None (a system header)."""
    here = (root / including).parent / name
    if here.is_file():
        return here.resolve().relative_to(root)
    own = layer_of(including)
    order = [own] + [l for l in INCLUDE_ROOTS if l != own]
    for layer in order:
        for inc in INCLUDE_ROOTS[layer]:
            p = root / inc / name
            if p.is_file():
                return p.resolve().relative_to(root)
    return None


def include_violations(root, rel, text):
    own = layer_of(rel)
    out = []
    for n, line in enumerate(text.splitlines(), 1):
        m = INCLUDE.match(line)
        if not m:
            continue
        target = resolve(root, rel, m.group(1))
        if target is None:
            continue
        theirs = layer_of(target)
        if theirs is not None and theirs not in LAYERS[own]:
            out.append(f"{rel}:{n}: {own} includes {theirs}'s {target} "
                       f"({own} may include {', '.join(sorted(LAYERS[own]))})")
    return out


def is_stage_or_engine(rel):
    parts = rel.parts
    if parts[0] in ("dpd_driver", "mpm_driver") and parts[1] in ("stage", "engine"):
        return True
    if parts[0] == "md_driver" and rel.suffix == ".cpp" and rel.name.startswith("md_"):
        return True
    return parts[0] == "coupler" and parts[1] in ("stages", "fit")


def strip_comment_and_strings(line):
    code = line.split("//", 1)[0]
    return code


def keyed_reads(text):
    """(line number, function name) of every string-keyed read outside a reader."""
    found = []
    functions = []  # (indent, name) of the definitions the line is inside
    pending = None  # a definition whose signature has not reached its '{' yet
    for n, line in enumerate(text.splitlines(), 1):
        stripped = line.lstrip()
        indent = len(line) - len(stripped)
        while functions and stripped.startswith("}") and indent <= functions[-1][0]:
            functions.pop()
        if stripped and not stripped.startswith(("//", "#", "}", "return", "if", "for", "while",
                                                 "switch", "else", "case")) \
                and not NOT_FUNCTION.match(stripped):
            m = FUNCTION_START.match(stripped)
            if m and not stripped.rstrip().endswith(";"):
                pending = (indent, m.group(1))
        if pending and line.rstrip().endswith("{") and pending[0] <= indent:
            functions.append(pending)
            pending = None
            if line.rstrip().endswith("}"):
                functions.pop()
        elif pending and line.rstrip().endswith(";"):
            pending = None
        code = RESULT_WRITE.sub("", strip_comment_and_strings(line))
        if not KEYED_READ.search(code):
            continue
        function = functions[-1][1] if functions else None
        if function and (function.endswith("from_yaml") or function.startswith("check")):
            continue
        found.append((n, function or "?"))
    return found


def check(root):
    problems = []
    for layer in LAYERS:
        for path in sorted((root / layer).rglob("*")):
            if not path.is_file() or not SOURCE.search(path.name):
                continue
            rel = path.relative_to(root)
            text = path.read_text(errors="replace")
            problems += include_violations(root, rel, text)
            if not is_stage_or_engine(rel):
                continue
            reads = keyed_reads(text)
            if reads:
                where = ", ".join(f"{n} ({f})" for n, f in reads[:6])
                more = "" if len(reads) <= 6 else f" and {len(reads) - 6} more"
                problems.append(
                    f"{rel}: {len(reads)} parameter reads by string key outside a from_yaml "
                    f"reader: lines {where}{more}")
    return problems


def main(argv):
    if not argv:
        sys.exit(__doc__)
    root = Path(argv[0]).resolve()
    problems = check(root)
    for p in problems:
        print(p)
    if problems:
        print(f"layers: {len(problems)} violation(s)")
        return 1
    print("layers: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
