"""The GeoJSON export and its QML style, opened by QGIS itself (issue 23).

Runs only where a Python with PyQGIS is found (Debian: ``apt-get install python3-qgis
qgis-providers``; ``ROCKSCREEN_QGIS_PYTHON`` names another interpreter); skips otherwise.
QGIS loads the layer, applies the style, every tower's ``risk_class`` has a category with
the report's colour, labels are on, and the map renders.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.assess.tower_summary import base_summary_row
from rockscreen.stations.inventory import Tower

SCRIPT = r"""
import json, os, sys
from qgis.core import QgsApplication, QgsVectorLayer, QgsMapSettings, QgsMapRendererParallelJob
from qgis.PyQt.QtCore import QSize
app = QgsApplication([], False)
app.initQgis()
layer = QgsVectorLayer(sys.argv[1], "towers", "ogr")
message, ok = layer.loadNamedStyle(sys.argv[2])
renderer = layer.renderer()
categories = {c.value(): c.symbol().color().name() for c in renderer.categories()}
settings = QgsMapSettings()
settings.setLayers([layer])
settings.setExtent(layer.extent().buffered(0.05))
settings.setOutputSize(QSize(400, 300))
job = QgsMapRendererParallelJob(settings)
job.start()
job.waitForFinished()
print(json.dumps({
    "valid": layer.isValid(), "features": layer.featureCount(), "style_ok": ok,
    "renderer": renderer.type(), "attribute": renderer.classAttribute(),
    "categories": categories, "labels": layer.labelsEnabled(),
    "values": sorted({f["risk_class"] for f in layer.getFeatures()}),
    "rendered": not job.renderedImage().isNull(),
}))
sys.stdout.flush()
os._exit(0)  # QGIS 3.22 can crash in exitQgis() on a headless machine; nothing left to save
"""


def _qgis_python() -> str:
    candidates = [
        os.environ.get("ROCKSCREEN_QGIS_PYTHON", ""),
        shutil.which("python3") or "",
        "/usr/bin/python3",  # the system Python, where Debian installs PyQGIS
    ]
    for python in filter(None, candidates):
        probe = subprocess.run(
            [python, "-c", "import qgis.core"], capture_output=True, timeout=60, check=False
        )
        if probe.returncode == 0:
            return python
    pytest.skip("no Python with PyQGIS (apt-get install python3-qgis qgis-providers)")


def test_qgis_opens_the_layer_with_its_style(tmp_path):
    python = _qgis_python()
    classes = ["very_high", "high", "moderate", "meets"]
    towers = [
        Tower(id=f"T{i}", width_m=2, height_m=10, lat=42.3 + 0.01 * i, lon=13.4)
        for i in range(len(classes))
    ]
    rows = [base_summary_row(site) for site in tower_sites(towers, 0.001)]
    for row, cls in zip(rows, classes, strict=True):
        row["risk_class"] = cls
    archive = tmp_path / "a.h5"
    write_risk_archive(archive, "assess", {"summary": rows}, {})
    layer = tmp_path / "towers.geojson"
    result = CliRunner().invoke(main, ["export", str(archive), "--geojson", str(layer)])
    assert result.exit_code == 0, result.output
    done = subprocess.run(
        [python, "-c", SCRIPT, str(layer), str(layer.with_suffix(".qml"))],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
        env={**os.environ, "QT_QPA_PLATFORM": "offscreen"},
    )
    assert done.returncode == 0, done.stderr[-2000:]
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    assert seen["valid"] and seen["style_ok"] and seen["features"] == len(classes)
    assert seen["renderer"] == "categorizedSymbol" and seen["attribute"] == "risk_class"
    assert seen["labels"] and seen["rendered"]
    for value in seen["values"]:  # every tower has its category, in the report's colour
        assert value in seen["categories"], value
        colour = RISK_COLOURS.get(value.split(" (")[0])
        assert colour is None or seen["categories"][value].lower() == colour.lower()
