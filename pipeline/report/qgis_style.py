"""QGIS layer styles (``.qml``) for the GeoJSON export: towers by risk band or by class.

An assess export whose towers have a screening risk (``risk_band``, docs/risk.md "The
screening risk in assess") gets ``NAME.qml`` coloured by the band (:func:`band_style_qml`:
``top_10`` to ``rest``, an uncertain band drawn with a dashed outline) and the code's class
style beside it as ``NAME.class.qml`` (Layer Properties > Symbology > Style > Load Style);
any other export gets the class style as ``NAME.qml``. The class style:

QGIS loads ``NAME.qml`` beside ``NAME.geojson`` as the layer's default style when the
layer is added (Layer Properties > Symbology > Style > Load Default Style otherwise).
The style is QGIS's QML, an XML document: one categorised renderer on the
``risk_class`` property, one circle marker per class in the report's colours
(:data:`rockscreen.pipeline.report.maps.RISK_COLOURS`, Okabe & Ito), a black outline,
and a grey marker for any other value. The towers are labelled with their ``id``.

``risk_class`` is one word of its scale (:mod:`rockscreen.pipeline.verdict.scales`), so no
value is split. An assess tower whose ``meets`` rests on rigid overturning alone
(``completeness`` ``rocking_only``) is counted ``incomplete`` everywhere else; here its
``meets`` marker takes the ``incomplete`` colour through a data-defined fill colour on
that column (:data:`INCOMPLETE_EXPRESSION`), and the category's label says so.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from xml.etree import ElementTree as ET

from rockscreen.pipeline.archive.atomic import write_text_atomic
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.report.values import JSONValue
from rockscreen.pipeline.verdict.scales import INCOMPLETE, SAFETY_CLASS, Completeness

__all__ = [
    "BAND_COLOURS",
    "band_style_qml",
    "class_style_path",
    "risk_style_qml",
    "write_risk_style",
]

#: Colour of each screening-risk band (Okabe & Ito), riskiest first.
BAND_COLOURS = {
    "top_10": "#D55E00",
    "top_25": "#E69F00",
    "top_50": "#F0E442",
    "rest": "#56B4E9",
}
#: QGIS expression of the outline of a tower whose band is uncertain: dashed.
UNCERTAIN_OUTLINE_EXPRESSION = "CASE WHEN \"risk_band_uncertain\" = 'yes' THEN 'dash' END"

#: Colour of a class the report does not know (and of features without a class).
OTHER_COLOUR = "#999999"


def _rgba(colour: str) -> str:
    """Return ``"r,g,b,255"`` (QGIS's colour property) for ``#rrggbb``."""
    return ",".join(str(int(colour[i : i + 2], 16)) for i in (1, 3, 5)) + ",255"


#: QGIS expression of the fill colour of a ``meets`` tower: the ``incomplete`` colour when its
#: verdict rests on rigid overturning alone, else NULL (the category's own colour).
INCOMPLETE_EXPRESSION = (
    f"CASE WHEN \"completeness\" = '{Completeness.ROCKING_ONLY.value}' "
    f"THEN '{_rgba(RISK_COLOURS[INCOMPLETE])}' END"
)


def _data_defined_fill(layer: ET.Element, expression: str, prop: str = "fillColor") -> None:
    """Give a symbol layer a data-defined property (QGIS 3 property collection).

    ``prop``: ``fillColor`` (the default) or ``outlineStyle``.
    """
    props = ET.SubElement(layer, "data_defined_properties")
    collection = ET.SubElement(props, "Option", {"type": "Map"})
    ET.SubElement(collection, "Option", {"type": "QString", "name": "name", "value": ""})
    properties = ET.SubElement(collection, "Option", {"type": "Map", "name": "properties"})
    fill = ET.SubElement(properties, "Option", {"type": "Map", "name": prop})
    ET.SubElement(fill, "Option", {"type": "bool", "name": "active", "value": "true"})
    ET.SubElement(fill, "Option", {"type": "QString", "name": "expression", "value": expression})
    ET.SubElement(fill, "Option", {"type": "int", "name": "type", "value": "3"})
    ET.SubElement(collection, "Option", {"type": "QString", "name": "type", "value": "collection"})


def _symbol(
    parent: ET.Element,
    name: str,
    colour: str,
    fill_expression: str = "",
    outline_expression: str = "",
) -> None:
    symbol = ET.SubElement(
        parent,
        "symbol",
        {"type": "marker", "name": name, "alpha": "1", "clip_to_extent": "1", "force_rhr": "0"},
    )
    layer = ET.SubElement(symbol, "layer", {"class": "SimpleMarker", "enabled": "1", "pass": "0"})
    props = {
        "name": "circle",
        "color": _rgba(colour),
        "outline_color": "0,0,0,255",
        "outline_style": "solid",
        "outline_width": "0.3",
        "outline_width_unit": "MM",
        "size": "3.2",
        "size_unit": "MM",
    }
    for key, value in props.items():
        ET.SubElement(layer, "prop", {"k": key, "v": value})
    if fill_expression:
        _data_defined_fill(layer, fill_expression)
    if outline_expression:
        _data_defined_fill(layer, outline_expression, "outlineStyle")


def risk_style_qml(classes: Sequence[str], attribute: str = "risk_class") -> str:
    """Return a QGIS style (QML) categorising point features by their risk class.

    Parameters
    ----------
    classes : sequence of str
        The values of ``attribute`` in the layer (``"high"``, ``"meets"``: words of their
        scale), one category each, worst first in the report's order; a value the report
        does not know takes the grey of :data:`OTHER_COLOUR`.
    attribute : str, optional
        The property holding the class.

    Returns
    -------
    str
        The XML document (UTF-8 declaration, QGIS's ``<!DOCTYPE qgis>``).
    """
    rank = {name: i for i, name in enumerate(RISK_COLOURS)}
    values = sorted(dict.fromkeys(classes), key=lambda v: (rank.get(v, 99), v))
    root, categories, symbols = _renderer(attribute)
    for i, value in enumerate(values):
        meets = value == SAFETY_CLASS.classes[0]
        label = f"{value} (light blue: {INCOMPLETE}, rocking only)" if meets else value
        ET.SubElement(
            categories,
            "category",
            {"symbol": str(i), "value": value, "label": label, "render": "true"},
        )
        colour = RISK_COLOURS.get(value, OTHER_COLOUR)
        _symbol(symbols, str(i), colour, INCOMPLETE_EXPRESSION if meets else "")
    return _document(root, categories, symbols, len(values))


def band_style_qml(bands: Sequence[str]) -> str:
    """Return a QGIS style (QML) categorising towers by their screening-risk band.

    Parameters
    ----------
    bands : sequence of str
        The ``risk_band`` values of the layer; one category each, riskiest first
        (:data:`BAND_COLOURS`; another value grey); a tower whose band is uncertain
        (``risk_band_uncertain`` ``yes``) has a dashed outline.

    Returns
    -------
    str
        The XML document.
    """
    rank = {name: i for i, name in enumerate(BAND_COLOURS)}
    values = sorted(dict.fromkeys(b for b in bands if b), key=lambda v: (rank.get(v, 99), v))
    root, categories, symbols = _renderer("risk_band")
    for i, value in enumerate(values):
        label = f"{value} (dashed: uncertain band)"
        ET.SubElement(
            categories,
            "category",
            {"symbol": str(i), "value": value, "label": label, "render": "true"},
        )
        colour = BAND_COLOURS.get(value, OTHER_COLOUR)
        _symbol(symbols, str(i), colour, outline_expression=UNCERTAIN_OUTLINE_EXPRESSION)
    return _document(root, categories, symbols, len(values))


def _renderer(attribute: str) -> tuple[ET.Element, ET.Element, ET.Element]:
    """Return the document's root, its categories and its symbols (a categorised renderer)."""
    root = ET.Element("qgis", {"version": "3.22.0", "styleCategories": "Symbology|Labeling"})
    renderer = ET.SubElement(
        root,
        "renderer-v2",
        {
            "type": "categorizedSymbol",
            "attr": attribute,
            "symbollevels": "0",
            "forceraster": "0",
            "enableorderby": "0",
        },
    )
    categories = ET.SubElement(renderer, "categories")
    symbols = ET.SubElement(renderer, "symbols")
    return root, categories, symbols


def _document(root: ET.Element, categories: ET.Element, symbols: ET.Element, n: int) -> str:
    """Return the QML text: the "other values" category and the labels (``id``) added."""
    # The "all other values" category: an empty value.
    other = str(n)
    ET.SubElement(
        categories,
        "category",
        {"symbol": other, "value": "", "label": "other", "render": "true"},
    )
    _symbol(symbols, other, OTHER_COLOUR)
    labeling = ET.SubElement(root, "labeling", {"type": "simple"})
    settings = ET.SubElement(labeling, "settings", {"calloutType": "simple"})
    ET.SubElement(
        settings,
        "text-style",
        {"fieldName": "id", "isExpression": "0", "fontSize": "8", "textColor": "0,0,0,255"},
    )
    buffer = ET.SubElement(settings, "text-buffer")
    buffer.attrib.update({"bufferDraw": "1", "bufferSize": "0.8", "bufferColor": "255,255,255,255"})
    ET.SubElement(settings, "placement", {"placement": "0", "dist": "1"})
    ET.indent(root)
    return (
        "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
        + ET.tostring(root, encoding="unicode")
        + "\n"
    )


def write_risk_style(features: Sequence[Mapping[str, JSONValue]], geojson: str | Path) -> Path:
    """Write the QGIS style beside a GeoJSON file (``NAME.qml``) and return its path.

    Parameters
    ----------
    features : sequence of mapping
        The GeoJSON features (their ``properties`` hold ``risk_class``).
    geojson : str or Path
        The GeoJSON file; the style gets its name with the suffix ``.qml``, which QGIS
        loads as the layer's default style.

    Returns
    -------
    Path
        The ``.qml`` file QGIS loads (written atomically): by ``risk_band`` when the towers
        have one, the class style then beside it (:func:`class_style_path`).
    """
    props = [f.get("properties", {}) for f in features]
    classes = [str(p.get("risk_class")) for p in props if p.get("risk_class") is not None]
    bands = [str(p.get("risk_band")) for p in props if p.get("risk_band")]
    out = Path(geojson).with_suffix(".qml")
    if bands:
        write_text_atomic(class_style_path(geojson), risk_style_qml(classes))
        write_text_atomic(out, band_style_qml(bands))
    else:
        write_text_atomic(out, risk_style_qml(classes))
    return out


def class_style_path(geojson: str | Path) -> Path:
    """Return the class style's file beside a GeoJSON coloured by band: ``NAME.class.qml``."""
    return Path(geojson).with_suffix(".class.qml")
