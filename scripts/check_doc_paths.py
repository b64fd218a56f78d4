#!/usr/bin/env python3
"""Path check for the documentation: every repository path that README.md and docs/*.md name must
exist, so a moved file cannot leave a page pointing at its old place.

What is checked, in each page:

- code: every inline `code span` (it may run over two lines) and every ``` fenced block ```. A word
  in it that starts with one of the repository's top folders (src/, tests/, scripts/, bench/,
  meshes/, docs/, fuzz/, .ci/, third_party/, optionally after "./") is a path relative to the
  repository root. A trailing ":LINE" or ":LINE-LINE" is dropped, "*" matches as in a shell glob,
  and "<name>" stands for one path component (`tests/<module>`). Words under ../shared (or any
  "../" path) are outside the repository and skipped; so are build outputs (build/, build-asan/:
  not in the list above). Indented (four-space) code blocks are not read: write commands that
  name paths in fenced blocks.
- links: every [text](target) and ![alt](target) whose target is not a URL, relative to the
  page's own folder, as Markdown resolves it. A "#section" part must name a heading of the target
  page (or of the page itself), as GitHub makes its anchors: lower case, punctuation dropped,
  spaces turned into "-".

The escape, for paths that a command in the page creates (an output name in an example, a folder
a script makes): an HTML comment in the same page, invisible in the rendered page,

    <!-- check_doc_paths: created PATH [PATH ...] -->

Each PATH is written as in the page and is then not required to exist. An escape that names a
path the page does not mention, or one that exists, is an error too, so escapes do not go stale.

    scripts/check_doc_paths.py [ROOT]   (ROOT defaults to the repository; exit 1 naming page and line)
"""
import glob
import pathlib
import re
import sys

ROOTS = ("src/", "tests/", "scripts/", "bench/", "meshes/", "docs/", "fuzz/", ".ci/", "third_party/")
ESCAPE = re.compile(r"<!--\s*check_doc_paths:\s*created\s+(.*?)-->", re.S)
FENCE = re.compile(r"^(```|~~~)")
SPAN = re.compile(r"(`+)((?:(?!\n[ \t]*\n).)+?)\1", re.S)  # a span never crosses a blank line
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
WORD_SPLIT = re.compile(r"[\s'\"(),;=|{}\[\]]+")


def candidates(text):
    """Repository paths named in a piece of code text."""
    for word in WORD_SPLIT.split(text):
        word = word.rstrip(".:,")
        if word.startswith("./"):
            word = word[2:]
        if not word.startswith(ROOTS):
            continue
        word = re.sub(r":\d+(-\d+)?$", "", word)
        yield word


def exists(root, path):
    pattern = re.sub(r"<[^<>/]+>", "*", path)
    if any(ch in pattern for ch in "*?["):
        return bool(glob.glob(str(root / pattern)))
    return (root / pattern).exists()


def code_pieces(text):
    """(line number, code text) for every fenced block line and inline code span of a page."""
    lines = text.split("\n")
    prose, fenced = [], []
    inside = False
    for number, line in enumerate(lines, 1):
        if FENCE.match(line.lstrip()):
            inside = not inside
            prose.append("")
            continue
        if inside:
            fenced.append((number, line))
            prose.append("")
        else:
            prose.append(line)
    joined = "\n".join(prose)
    joined = ESCAPE.sub(lambda m: "\n" * m.group(0).count("\n"), joined)
    pieces = list(fenced)
    for m in SPAN.finditer(joined):
        pieces.append((joined.count("\n", 0, m.start()) + 1, m.group(2)))
    return pieces, joined


def anchors(page):
    """The GitHub anchors of a Markdown page's headings."""
    found, seen = set(), {}
    inside = False
    for line in page.read_text(encoding="utf-8").split("\n"):
        if FENCE.match(line.lstrip()):
            inside = not inside
        m = None if inside else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        slug = re.sub(r"[^\w\- ]", "", m.group(1).lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        found.add(slug if n == 0 else f"{slug}-{n}")
    return found


def check_page(root, page):
    errors = []
    text = page.read_text(encoding="utf-8")
    name = page.relative_to(root)
    created = set()
    for m in ESCAPE.finditer(text):
        created.update(m.group(1).split())
    mentioned = set()
    pieces, prose = code_pieces(text)
    for number, code in pieces:
        for path in candidates(code):
            mentioned.add(path)
            if path not in created and not exists(root, path):
                errors.append(f"{name}:{number}: `{path}` does not exist")
    for m in LINK.finditer(prose):
        target, _, anchor = m.group(1).partition("#")
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("../shared"):
            continue
        number = prose.count("\n", 0, m.start()) + 1
        resolved = (page.parent / target).resolve() if target else page.resolve()
        if anchor and resolved.suffix == ".md" and resolved.exists() and anchor not in anchors(resolved):
            errors.append(f"{name}:{number}: link to {m.group(1)}: no such heading in {target or 'this page'}")
        if not target:
            continue
        try:
            relative = resolved.relative_to(root.resolve())
        except ValueError:
            continue  # outside the repository
        mentioned.add(str(relative))
        if str(relative) not in created and not resolved.exists():
            errors.append(f"{name}:{number}: link to {target} does not exist")
    for path in sorted(created):
        if path not in mentioned:
            errors.append(f"{name}: escape names {path}, which the page does not mention")
        elif exists(root, path):
            errors.append(f"{name}: escape names {path}, which exists: drop it from the escape")
    return errors, len(mentioned)


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    pages = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    errors, count = [], 0
    for page in pages:
        if not page.exists():
            errors.append(f"{page.relative_to(root)}: missing")
            continue
        page_errors, page_count = check_page(root, page)
        errors += page_errors
        count += page_count
    for e in errors:
        print(e, file=sys.stderr)
    if errors:
        sys.exit(1)
    print(f"check_doc_paths: {len(pages)} pages, {count} paths and links, every one exists")


if __name__ == "__main__":
    main()
