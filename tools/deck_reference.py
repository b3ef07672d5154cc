#!/usr/bin/env python3
"""Keep doc/deck-reference.md whole: its Part 2 is doc/extensions.md from its
first '## ' section on. `tools/deck_reference.py` rewrites Part 2;
`--check` only says whether it is current (exit 1 if not; the docs.cards test).
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MARK = "# Part 2: extensions and interpretations\n"


def expected():
    ref = open(os.path.join(ROOT, "doc", "deck-reference.md")).read()
    ext = open(os.path.join(ROOT, "doc", "extensions.md")).read()
    return ref, ref[:ref.index(MARK)] + MARK + ext[ext.index("\n## "):]


def main():
    ref, want = expected()
    if "--check" in sys.argv[1:]:
        if ref != want:
            print("FAIL: doc/deck-reference.md Part 2 differs from doc/extensions.md "
                  "(run tools/deck_reference.py)")
            return 1
        print("doc/deck-reference.md Part 2 is doc/extensions.md")
        return 0
    open(os.path.join(ROOT, "doc", "deck-reference.md"), "w").write(want)
    return 0


if __name__ == "__main__":
    sys.exit(main())
