#!/usr/bin/env python3
"""Layer check (issue 15): every #include "folder/..." under src/ must point at a folder below the
including one in the layer order the README writes on its line starting with "Layers:", e.g.

    Layers: util, optim → mesh → geometry → io, meshio → sparse → spectral → skeleton, mass → shape → cli

Levels are separated by "→"; within a level, a folder may include the ones listed before it
(meshio includes io, never the reverse). A folder under src/ missing from the line is an error
too, so a new folder gets a place before it gets code.

    scripts/check_layers.py [ROOT]      (ROOT defaults to the repository; exit 1 on a breach)
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
readme = (root / "README.md").read_text(encoding="utf-8")
line = next((l for l in readme.splitlines() if l.startswith("Layers:")), None)
if line is None:
    sys.exit("check_layers: README.md has no line starting with 'Layers:'")

# rank: a folder may include every folder of a smaller rank.
rank = {}
for level, group in enumerate(line[len("Layers:"):].split("→")):
    for position, name in enumerate(n.strip().strip("`") for n in group.split(",")):
        if name:
            rank[name] = (level, position)

src = root / "src"
errors = []
for folder in sorted(p.name for p in src.iterdir() if p.is_dir()):
    if folder not in rank:
        errors.append(f"src/{folder}: not on the README's Layers: line")
include = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')
for path in sorted(src.rglob("*")):
    if path.suffix not in (".h", ".cpp") or path.parent.parent != src:
        continue
    own = path.parent.name
    for number, text in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        m = include.match(text)
        if not m or m.group(1) == own or own not in rank:
            continue
        target = m.group(1)
        if target not in rank:
            errors.append(f"{path.relative_to(root)}:{number}: includes {target}/, which is not on the Layers: line")
        elif rank[target] >= rank[own]:
            allowed = ", ".join(sorted((n for n in rank if rank[n] < rank[own]), key=lambda n: rank[n])) or "nothing"
            errors.append(f"{path.relative_to(root)}:{number}: {own} includes {target}/ (above it); {own} may include: {allowed}")

for e in errors:
    print(e, file=sys.stderr)
if errors:
    sys.exit(1)
print(f"check_layers: {len(rank)} folders, every include points down")
