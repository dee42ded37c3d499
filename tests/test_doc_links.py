# SPDX-License-Identifier: BSD-2-Clause
"""The documentation's links lead somewhere: every relative link of the README and docs/ names a file of
the project, every #anchor a heading of its page (GitHub's slug), and every prose reference of the form
`verify.md, "Whole runs and windows"` or `README "A first CI gate"` a heading or a bold paragraph lead
of that page."""

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
PAGES = [
    REPO / "README.md",
    *sorted((REPO / "docs").glob("*.md")),
    REPO / "tests" / "README.md",
    REPO / "examples" / "ci" / "README.md",
    REPO / "CHANGELOG.md",
]


def prose(text: str) -> str:
    """The text without its code blocks, whose brackets and quotes are code."""
    return re.sub(r"```.*?```", "", text, flags=re.S)


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, markup and punctuation dropped, blanks to hyphens. An
    underscore stays (in a code span or a word: `assert_trajectory`), unless it marks _emphasis_."""
    parts = re.split(r"(`[^`]*`)", heading.strip())
    markup = r"\*|(?<!\w)_|_(?!\w)|\[([^]]*)\]\([^)]*\)"
    text = "".join(p[1:-1] if p.startswith("`") else re.sub(markup, r"\1", p) for p in parts).lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(text: str) -> set:
    """A page's anchors: its headings' slugs (a repeated one gets -1, -2, ...) and explicit <a id/name>."""
    seen, out = {}, set()
    for heading in re.findall(r"^#{1,6}\s+(.*?)\s*$", prose(text), re.M):
        s = slug(heading)
        n = seen.get(s, 0)
        seen[s] = n + 1
        out.add(s if n == 0 else f"{s}-{n}")
    return out | set(re.findall(r'<a (?:id|name)="([^"]+)"', text))


def sections(text: str) -> set:
    """What a prose reference may name: headings, and the bold leads that open paragraphs and items."""
    body = prose(text)
    heads = {re.sub(r"[`*]", "", h).strip() for h in re.findall(r"^#{1,6}\s+(.*?)\s*$", body, re.M)}
    return heads | {re.sub(r"[`*]", "", b).strip(" .:") for b in re.findall(r"\*\*([^*]+)\*\*", body)}


def links(page: Path):
    """(target, anchor) of each relative markdown link of a page."""
    for target in re.findall(r"\]\(<?([^)\s>]+)>?\)", prose(page.read_text())):
        if re.match(r"[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
            continue
        path, _, anchor = target.partition("#")
        yield (page.parent / path).resolve() if path else page, anchor


def shown(path: Path) -> str:
    return str(path.relative_to(REPO) if REPO in path.parents else path)


def broken(page: Path) -> list:
    found = []
    for target, anchor in links(page):
        if not target.exists():
            found.append(f"{shown(target)}: no such file")
        elif anchor and target.suffix == ".md" and anchor not in anchors(target.read_text()):
            found.append(f"{shown(target)}#{anchor}: no such heading")
    for name, section in re.findall(r"([\w./-]+\.md)\]?(?:\([^)]*\))?\)?,\s*\"([^\"]+)\"", prose(page.read_text())):
        target = next((p for p in (page.parent / name, REPO / name, REPO / "docs" / name) if p.is_file()), None)
        if target is None:
            found.append(f"{name}: no such file")
        elif not any(s == section or s.startswith(section) for s in sections(target.read_text())):
            found.append(f'{name}, "{section}": no such heading or bold lead')
    for section in re.findall(r"README(?:'s|,)? \"([^\"]+)\"", prose(page.read_text())):  # the README's own
        if not any(s == section or s.startswith(section) for s in sections((REPO / "README.md").read_text())):
            found.append(f'README "{section}": no such heading or bold lead')
    return found


def test_the_checker_finds_what_is_broken(tmp_path):
    (tmp_path / "b.md").write_text(
        "# Two words\n\n## `pmdfmu run`: windows\n\n## `assert_trajectory` _as_ run_id\n\n**Golden traces** are ...\n"
    )
    page = tmp_path / "a.md"
    page.write_text(
        '[ok](b.md#two-words) [ok](b.md#pmdfmu-run-windows) [ok](https://x.org/#y) (b.md, "Golden traces")\n'
        "[ok](b.md#assert_trajectory-as-run_id) [bad](b.md#asserttrajectory-as-runid)\n"
        '[gone](c.md) [bad](b.md#three-words) (b.md, "Silver traces") README "Scripts"\n'
        "```\n[code](not/a/link.md)\n```\n"
    )
    assert broken(page) == [
        f"{tmp_path / 'b.md'}#asserttrajectory-as-runid: no such heading",
        f"{tmp_path / 'c.md'}: no such file",
        f"{tmp_path / 'b.md'}#three-words: no such heading",
        'b.md, "Silver traces": no such heading or bold lead',
        'README "Scripts": no such heading or bold lead',
    ]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_every_link_and_reference_of_the_documentation_resolves(page):
    assert not broken(page), f"{page.relative_to(REPO)}: {broken(page)}"
