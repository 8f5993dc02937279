"""Messages about the whole verdict (its record basis, its completeness)."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec(
        "basis.noncompliant",
        "basis not code-compliant (run with --allow-noncompliant): {detail}",
        "base non conforme alla norma (calcolo con --allow-noncompliant): {detail}",
    ),
)
