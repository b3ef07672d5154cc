#!/usr/bin/env python3
"""The layers of src/ (doc/architecture.md), checked from the Fortran text.

Each folder of src/ may `use` modules of the folders listed for it below and of
its own folder, nothing else, so the pipeline mesh -> DOFs -> assembly -> solver
-> output never reaches back. Element types are known in src/elements/ only:
outside it an ET_* constant may be named only in src/model/types.f90, where
they are numbered (ELEMENT_NAME_FILES); the rest of the program asks
superjoin_elements_traits. Also: no Fortran file over MAX_FILE_LINES lines.

usage: check_layers.py [SOURCE_ROOT]   (default: the repository of this script)
       check_layers.py --selftest     (a small tree with three violations is refused)
Prints one line per violation and exits 1 when there is any, else prints a
summary and exits 0."""
import os
import re
import sys

LAYERS = {   # folder -> folders it may use (besides itself)
    "utils": [],
    "model": ["utils"],
    "elements": ["utils", "model"],
    "deck": ["utils", "model", "elements"],
    "parallel": ["utils", "model"],
    "solvers": ["utils", "model", "parallel"],
    "assembly": ["utils", "model", "elements", "solvers"],
    "substructure": ["utils", "model", "elements", "solvers", "assembly"],
    "analysis": ["utils", "model", "elements", "parallel", "solvers", "assembly", "substructure"],
    "output": ["utils", "model", "elements"],
}
ELEMENT_NAME_FILES = {"src/model/types.f90"}
MAX_FILE_LINES = 1200
ROOT_MODULES = {"superjoin_kinds", "superjoin_error", "superjoin_config"}   # src/*.f90, generated config


def selftest():
    """A tree where output reaches analysis, deck names ET_S4 and a file is too long must give
    exactly those three violations; the same tree without them none."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        def write(rel, text):
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w") as f:
                f.write(text)
        write("src/analysis/a.f90", "module superjoin_analysis_a\nend module\n")
        write("src/output/o.f90", "module superjoin_output_o\n  use superjoin_analysis_a\nend module\n")
        write("src/deck/d.f90", "module superjoin_deck_d\n  ! ET_S8R in a comment is fine\n  k = ET_S4\nend module\n")
        write("src/utils/u.f90", "module superjoin_utils_u\n" + "\n" * MAX_FILE_LINES + "end module\n")
        bad = check(tmp)
        write("src/output/o.f90", "module superjoin_output_o\nend module\n")
        write("src/deck/d.f90", "module superjoin_deck_d\nend module\n")
        write("src/utils/u.f90", "module superjoin_utils_u\nend module\n")
        good = check(tmp)
    ok = len(bad) == 3 and any("uses superjoin_analysis_a" in b for b in bad) \
        and any("ET_S4)" in b for b in bad) and any("lines (at most" in b for b in bad) and not good
    print("\n".join(bad))
    print("check_layers selftest:", "ok" if ok else "FAILED")
    return 0 if ok else 1


def main():
    if sys.argv[1:] == ["--selftest"]:
        return selftest()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    problems = check(root)
    for p in problems:
        print(p)
    if problems:
        print(f"check_layers: {len(problems)} violation(s)")
        return 1
    print("check_layers: layers respected, element types named in src/elements only, no file over "
          f"{MAX_FILE_LINES} lines")
    return 0


def check(root):
    """The violations in the tree at root, one line each."""
    src = os.path.join(root, "src")
    texts, folder_of_module = {}, {}
    for dp, _, fs in os.walk(src):
        for f in sorted(fs):
            if not f.endswith(".f90"):
                continue
            p = os.path.join(dp, f)
            rel = os.path.relpath(p, root).replace(os.sep, "/")
            parts = rel.split("/")
            folder = parts[1] if len(parts) > 2 else "."
            text = open(p, encoding="utf-8", errors="replace").read()
            texts[rel] = (folder, text)
            for m in re.finditer(r"(?im)^\s*module\s+(?!procedure\b)(\w+)", text):
                folder_of_module[m.group(1).lower()] = folder
    problems = []
    for rel, (folder, text) in sorted(texts.items()):
        nlines = text.count("\n")
        if nlines > MAX_FILE_LINES:
            problems.append(f"{rel}: {nlines} lines (at most {MAX_FILE_LINES})")
        if folder == ".":
            continue
        if folder not in LAYERS:
            problems.append(f"{rel}: folder src/{folder} has no layer in check_layers.py")
            continue
        for ln, line in enumerate(text.split("\n"), 1):
            m = re.match(r"(?i)^\s*use\s*(?:,\s*\w+\s*::)?\s*(\w+)", line)
            if not m:
                continue
            mod = m.group(1).lower()
            used = folder_of_module.get(mod)
            if used is None or mod in ROOT_MODULES or used in (folder, "."):
                continue
            if used not in LAYERS[folder]:
                problems.append(f"{rel}:{ln}: src/{folder} uses {mod} of src/{used}, a layer above it")
        if folder != "elements" and rel not in ELEMENT_NAME_FILES:
            code = "\n".join(l.split("!")[0] for l in text.split("\n"))
            names = sorted(set(re.findall(r"\bET_[A-Z0-9]+\b", code)))
            if names:
                problems.append(f"{rel}: names element types outside src/elements ({', '.join(names[:4])}"
                                + (", ..." if len(names) > 4 else "") + "): ask superjoin_elements_traits")
    return problems


if __name__ == "__main__":
    sys.exit(main())
