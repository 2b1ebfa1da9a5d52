#!/usr/bin/env python3
"""Regenerate the tables the docs take from the program: every block between
"<!-- BEGIN oscidrum ARGS -->" and "<!-- END oscidrum ... -->" in README.md and docs/*.md becomes
the output of `oscidrum ARGS` (tests check that they are current).

    scripts/regen-docs.py [path to the oscidrum binary, default build/apps/cli/oscidrum]
"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
CLI = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build" / "apps" / "cli" / "oscidrum")
BLOCK = re.compile(r"(<!-- BEGIN oscidrum ([^>]*?) -->\n)(.*?)(<!-- END oscidrum [^>]*-->)", re.S)


def regenerate(text):
    def run(match):
        out = subprocess.run([CLI, *match.group(2).split()], check=True, capture_output=True,
                             text=True).stdout
        return match.group(1) + out + match.group(4)
    return BLOCK.sub(run, text)


for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
    old = path.read_text()
    new = regenerate(old)
    if new != old:
        path.write_text(new)
        print("regenerated", path.relative_to(ROOT))
