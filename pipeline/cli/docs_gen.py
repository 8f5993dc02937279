"""Generate the reference pages of ``docs/`` from the code: one command regenerates them all.

Run from the root of a clone::

    python -m rockscreen.pipeline.cli.docs_gen          # write the generated pages
    python -m rockscreen.pipeline.cli.docs_gen --check  # exit 1 naming the stale ones

What is generated, and from what (each page or section written once, here, never by hand):

- ``docs/cli.md``: every command, argument and option of the ``rockscreen`` click group
  (:data:`rockscreen.pipeline.cli.COMMANDS`): names, types, defaults and help, read from
  click itself;
- ``docs/archive_layout.md``: every archive kind of
  :data:`rockscreen.pipeline.archive.kinds.ARCHIVE_KINDS`, its tables and their columns with
  units (each reader's ``schema``: :mod:`~rockscreen.pipeline.archive.schema`,
  :mod:`~rockscreen.pipeline.archive.risk_schema`,
  :mod:`~rockscreen.pipeline.archive.sweep_archive`);
- the section between the ``inventory-columns`` markers of ``docs/inventory.md``: every
  inventory column of :mod:`rockscreen.stations.inventory_columns` (unit, type, required or
  group, allowed values or plausible range, meaning);
- the section between the ``config-keys`` markers of ``docs/campaign.md``: every
  configuration key (:func:`rockscreen.pipeline.config_schema.key_table_markdown`).

It is a module of ``cli`` (and not a ``rockscreen`` subcommand) because it reads the click
commands, which only ``cli`` may import, and because it writes into a clone's ``docs/``,
which an installed rockscreen does not have: it is a developer's tool, not a user's command.
The pages are rendered by :mod:`rockscreen.pipeline.cli.reference_pages`; this module puts
them in place. ``tests/test_docs_fresh.py`` regenerates every page in memory and compares.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Callable
from pathlib import Path

from rockscreen.pipeline.cli.reference_pages import (
    GENERATED_NOTE,
    REGENERATE,
    archive_layout_markdown,
    cli_markdown,
    inventory_columns_markdown,
)

__all__ = [
    "GENERATED_NOTE",
    "PAGES",
    "REGENERATE",
    "SECTIONS",
    "expected_pages",
    "main",
    "replace_section",
    "stale_pages",
]


# --------------------------------------------------------------------------- the pages


def replace_section(text: str, name: str, body: str, path: str) -> str:
    """Return ``text`` with the section between the ``name`` markers replaced by ``body``.

    The markers are the lines ``<!-- NAME:start ... -->`` and ``<!-- NAME:end -->``.

    Parameters
    ----------
    text : str
        The page.
    name : str
        The markers' name (``"inventory-columns"``).
    body : str
        The section's new text, ending with a newline.
    path : str
        The page's path, for the message.

    Returns
    -------
    str
        The page with the section replaced (the markers kept).

    Raises
    ------
    ValueError
        When the page lacks either marker (naming the page and the markers).
    """
    pattern = re.compile(
        rf"(^<!-- {re.escape(name)}:start[^\n]*-->\n)(.*?)(^<!-- {re.escape(name)}:end -->$)",
        re.S | re.M,
    )
    if not pattern.search(text):
        raise ValueError(
            f"{path}: no '<!-- {name}:start ... -->' ... '<!-- {name}:end -->' markers"
        )
    return pattern.sub(lambda m: m.group(1) + body + m.group(3), text, count=1)


def _config_keys_markdown() -> str:
    from rockscreen.pipeline.config_schema import key_table_markdown

    return key_table_markdown()


#: Whole pages: path under the clone -> function returning the page.
PAGES: dict[str, Callable[[], str]] = {
    "docs/cli.md": cli_markdown,
    "docs/archive_layout.md": archive_layout_markdown,
}
#: Sections of hand-written pages: (path, marker name, function returning the section).
SECTIONS: tuple[tuple[str, str, Callable[[], str]], ...] = (
    ("docs/inventory.md", "inventory-columns", inventory_columns_markdown),
    ("docs/campaign.md", "config-keys", _config_keys_markdown),
)


def expected_pages(root: str | Path) -> dict[str, str]:
    """Return every generated page as it should be: path under ``root`` -> text.

    Parameters
    ----------
    root : str or path-like
        The clone's root (its ``docs/`` holds the pages). The pages with generated sections
        are read from it and returned with those sections regenerated.

    Returns
    -------
    dict
        Relative path -> the page's expected text.
    """
    root = Path(root)
    pages = {path: make() for path, make in PAGES.items()}
    for path, name, make in SECTIONS:
        text = pages.get(path) or (root / path).read_text(encoding="utf-8")
        pages[path] = replace_section(text, name, make(), path)
    return pages


def stale_pages(root: str | Path) -> list[str]:
    """Return the generated pages under ``root`` that differ from what the code generates.

    Parameters
    ----------
    root : str or path-like
        The clone's root.

    Returns
    -------
    list of str
        The stale (or missing) pages' paths relative to ``root``; empty when all are fresh.
    """
    root = Path(root)
    return [
        path
        for path, text in expected_pages(root).items()
        if not (root / path).is_file() or (root / path).read_text(encoding="utf-8") != text
    ]


def main(argv: list[str] | None = None) -> int:
    """Write (or, with ``--check``, check) every generated page.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default ``sys.argv[1:]``): ``--root DIR``, ``--check``.

    Returns
    -------
    int
        The exit code: 0, or 1 when ``--check`` finds a stale page or there is no ``docs/``.
    """
    parser = argparse.ArgumentParser(
        prog=REGENERATE, description="Regenerate the reference pages of docs/ from the code."
    )
    parser.add_argument(
        "--root", default=".", help="the clone's root, holding docs/ (default: here)"
    )
    parser.add_argument(
        "--check", action="store_true", help="write nothing; exit 1 naming the stale pages"
    )
    args = parser.parse_args(argv)
    root = Path(args.root)
    if not (root / "docs").is_dir():
        print(f"{REGENERATE}: {root / 'docs'} is not a folder: run it from a clone's root")
        return 1
    if args.check:
        stale = stale_pages(root)
        for path in stale:
            print(f"{path} is stale: run {REGENERATE}")
        return 1 if stale else 0
    for path, text in expected_pages(root).items():
        target = root / path
        if not target.is_file() or target.read_text(encoding="utf-8") != text:
            target.write_text(text, encoding="utf-8")
            print(f"wrote {path}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
