"""Rendering the HTML report imports no risk computation, no case engine and no solver.

The page reads an archive and renders its stored values from the vocabulary (the verdict
package, the archive's schemas, the registry's model names and labels); it needs neither
the fits, the IDA, the stripes, the code checks' computations nor the engine's case loop.
Each check runs in a fresh interpreter, so what another test imported does not count.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

#: Engine modules the page may load: the model registry (names, labels) and the models'
#: declarations it loads on first use, the solver table those name (loaded on first use),
#: the stored result types.
ENGINE_ALLOWED = (
    "rockscreen.pipeline.engine",
    "rockscreen.pipeline.engine.registry",
    "rockscreen.pipeline.engine.results",
    "rockscreen.pipeline.engine.solvers",
)
#: Modules of ``risk/`` that are vocabulary, not computation: the package (a docstring) and
#: the code checks' registry (each check's id, part, family, label and the summary columns it
#: reads: declarations over stored rows), which a page may name its checks from.
RISK_VOCABULARY = (
    "rockscreen.pipeline.risk",
    "rockscreen.pipeline.risk.checks",
    "rockscreen.pipeline.risk.checks.registry",
)
#: Libraries of the computation (the fits, the compiled solver).
LIBRARIES = ("scipy", "numba")

SCRIPT = textwrap.dedent(
    """
    import importlib, json, math, pathlib, pkgutil, sys, tempfile

    from rockscreen.pipeline.archive.risk_archive import write_risk_archive
    from rockscreen.pipeline.report import html
    from rockscreen.pipeline.report.html import adapters
    from rockscreen.pipeline.report.presenters import PRESENTERS

    for info in pkgutil.iter_modules(adapters.__path__, adapters.__name__ + "."):
        importlib.import_module(info.name)
    for presenter in PRESENTERS.values():
        importlib.import_module(presenter.report.split(":")[0])

    row = {
        "id": "T1", "name": "first", "lat_deg": 41.0, "lon_deg": 14.4, "soil_class": "C",
        "soil_class_source": "default", "fragility_median_g": 0.3, "fragility_beta": 0.4,
        "annual_rate_overturning_per_y": 2e-3, "p_overturning_50y": 0.095,
        "capacity_pga_g": 0.3, "capacity_return_period_y": 500.0, "safety_index": 0.7,
        "acceleration_factor": 0.8, "risk_class": "moderate", "note": "",
    }
    stripes = [
        {"tower_id": "T1", "return_period_y": tr, "ag_g": ag, "n_records": 7,
         "n_overturned": k}
        for tr, ag, k in ((50.0, 0.1, 0), (475.0, 0.25, 3), (2475.0, 0.45, 6))
    ]
    folder = pathlib.Path(tempfile.mkdtemp())
    archive = folder / "assess.h5"
    write_risk_archive(archive, "assess", {"summary": [row], "stripes": stripes}, {})
    for lang in ("en", "it"):
        page = html.build_report(archive, folder / f"report_{lang}.html", lang)
        assert "T1" in page.read_text(encoding="utf-8")
    print(json.dumps({"modules": sorted(sys.modules)}))
    """
)


def _closure() -> dict:
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=300, check=False
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_rendering_the_report_imports_no_risk_computation_nor_engine():
    closure = _closure()
    modules = closure["modules"]
    risk = [
        m for m in modules if m.startswith("rockscreen.pipeline.risk") and m not in RISK_VOCABULARY
    ]
    assert not risk, f"the report imports the risk computation: {risk}"
    engine = [
        m
        for m in modules
        if m.startswith("rockscreen.pipeline.engine")
        and m not in ENGINE_ALLOWED
        and not m.startswith("rockscreen.pipeline.engine.models")
    ]
    assert not engine, f"the report imports the case engine: {engine}"
    solver = [m for m in modules if m.startswith("rockscreen.solver.") and "kernel" in m]
    assert not solver, f"the report imports the compiled solver: {solver}"
    libraries = sorted({m.split(".")[0] for m in modules} & set(LIBRARIES))
    assert not libraries, f"the report imports {libraries}"
