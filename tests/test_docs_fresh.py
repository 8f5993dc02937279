"""The generated reference pages are fresh, and the README is a front page that points to them.

``docs/cli.md``, ``docs/archive_layout.md``, the inventory-columns section of
``docs/inventory.md`` and the config-keys section of ``docs/campaign.md`` are written by
``python -m rockscreen.pipeline.cli.docs_gen`` from the click commands, the archive kinds'
schemas, the inventory's column registry and the configuration's key table. Each test here
regenerates them in memory and compares with the committed files.
"""

from __future__ import annotations

import re
from pathlib import Path

import click
import pytest

from rockscreen.pipeline.archive.kinds import ARCHIVE_KINDS
from rockscreen.pipeline.cli import COMMANDS, main
from rockscreen.pipeline.cli.docs_gen import (
    GENERATED_NOTE,
    PAGES,
    REGENERATE,
    SECTIONS,
    expected_pages,
    replace_section,
    stale_pages,
)
from rockscreen.stations.inventory_columns import COLUMNS

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
#: Every page the generator writes (whole, or a section of it).
GENERATED = sorted({*PAGES, *(path for path, _, _ in SECTIONS)})


@pytest.fixture(scope="module")
def expected() -> dict[str, str]:
    """Every generated page as the code generates it now."""
    return expected_pages(ROOT)


def test_the_generator_writes_the_pages_it_names(expected):
    assert sorted(expected) == GENERATED


@pytest.mark.parametrize("page", GENERATED)
def test_generated_page_is_fresh(page, expected):
    committed = (ROOT / page).read_text(encoding="utf-8") if (ROOT / page).is_file() else ""
    assert committed == expected[page], (
        f"{page} is stale (the code changed since it was generated): run `{REGENERATE}` "
        "from the repository root and commit the result"
    )


def test_the_check_reports_a_stale_page(tmp_path, expected):
    for page, text in expected.items():
        (tmp_path / page).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / page).write_text(text, encoding="utf-8")
    assert stale_pages(tmp_path) == []
    (tmp_path / "docs/cli.md").write_text(expected["docs/cli.md"] + "edited\n", encoding="utf-8")
    assert stale_pages(tmp_path) == ["docs/cli.md"]


def test_a_page_without_its_markers_is_refused():
    with pytest.raises(ValueError, match="inventory-columns:start"):
        replace_section("no markers\n", "inventory-columns", "x\n", "docs/inventory.md")


def _commands() -> list[tuple[str, click.Command]]:
    root = main.make_context("rockscreen", [], resilient_parsing=True)
    return [(name, main.get_command(root, name)) for name in COMMANDS]


def test_cli_md_has_every_command_and_option(expected):
    text = expected["docs/cli.md"]
    assert GENERATED_NOTE in text
    for name, command in _commands():
        assert f"\n## rockscreen {name}\n" in text
        section = text.split(f"\n## rockscreen {name}\n")[1].split("\n## rockscreen ")[0]
        for param in command.params:
            if isinstance(param, click.Option) and not param.hidden:
                for spelling in param.opts:
                    assert f"`{spelling}" in section, f"{name}: {spelling} missing"
            if param.help:
                assert " ".join(param.help.split()) in section.replace("\\|", "|")


def test_archive_layout_has_every_kind_table_and_column(expected):
    text = expected["docs/archive_layout.md"]
    for kind, reader in ARCHIVE_KINDS.items():
        section = text.split(f"\n## `{kind}` archives\n")[1].split("\n## `")[0]
        for table, columns in reader.schema.items():
            part = section.split(f"\n### `/{table}`\n")[1].split("\n### ")[0]
            for column, units in columns.items():
                cell = "text" if units == "" else f"`{units}`"
                assert f"| `{column}` | {cell} |" in part, f"{kind} /{table} {column}"


def test_inventory_md_has_every_column_once():
    text = (ROOT / "docs" / "inventory.md").read_text(encoding="utf-8")
    for column, (unit, meaning) in COLUMNS.items():
        rows = re.findall(rf"^\| `{re.escape(column)}` \|.*$", text, re.M)
        assert len(rows) == 1, f"{column}: {len(rows)} rows in docs/inventory.md"
        assert f"| {'–' if unit == '-' else unit} |" in rows[0], f"{column}: unit {unit}"
        assert " ".join(meaning.split()) in rows[0]


# --------------------------------------------------------------------------- the README


def test_readme_is_a_front_page():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) < 200, f"README.md has {len(lines)} lines: move reference to docs/"


@pytest.mark.parametrize(
    "page", sorted(str(path.relative_to(ROOT)) for path in (ROOT / "docs").glob("*.md"))
)
def test_readme_links_to_the_docs(page):
    text = README.read_text(encoding="utf-8")
    assert f"]({page})" in text, f"README.md does not link to {page}"
    assert (ROOT / page).is_file()


def _anchors(page: Path) -> set[str]:
    """Return the GitHub anchors of a Markdown page's headings."""
    headings = re.findall(r"^#+ (.+)$", page.read_text(encoding="utf-8"), re.M)
    return {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-") for h in headings}


def test_every_link_between_the_pages_resolves():
    pages = [README, *sorted((ROOT / "docs").glob("*.md"))]
    broken = []
    for page in pages:
        text = page.read_text(encoding="utf-8")
        for target, anchor in re.findall(r"\]\(([\w./-]+\.md)(?:#([\w-]+))?\)", text):
            path = page.parent / target
            if not path.is_file() or (anchor and anchor not in _anchors(path)):
                broken.append(f"{page.relative_to(ROOT)} -> {target}#{anchor}")
    assert not broken, f"broken links: {broken}"


def test_readme_keeps_the_seed_paper_and_the_dependencies():
    text = " ".join(README.read_text(encoding="utf-8").split())
    assert "Di Gennaro, Guadagnuolo and Monaco (Buildings 2023, 13, 762)" in text
    assert "## Why these dependencies" in README.read_text(encoding="utf-8")
