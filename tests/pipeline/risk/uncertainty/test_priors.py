"""The priors of what an inventory does not say (``risk.uncertainty.priors``, ``.region``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import ConfigError
from rockscreen.pipeline.risk.checks.confidence import MASONRY_TYPES
from rockscreen.pipeline.risk.uncertainty import TowerPriors, read_region_priors
from rockscreen.pipeline.risk.uncertainty.belfry import BelfryPriors
from rockscreen.pipeline.risk.uncertainty.distributions import (
    Categorical,
    LogNormal,
    Point,
    Taper,
    Uniform,
)
from rockscreen.pipeline.risk.uncertainty.priors import (
    BELL_TOWER_MASONRY_TYPES,
    TAPER_PRISMATIC_SHARE,
    WALL_RATIO_MAX,
    WALL_RATIO_MEDIAN,
    RegionPriors,
    strength_prior,
    unit_weight_prior,
)
from rockscreen.stations.inventory import Tower

TOWER = Tower(id="G", width_m=6.0, depth_m=5.0, height_m=34.0, lat=42.35, lon=13.40)


@pytest.mark.parametrize(
    "prior",
    [
        Uniform(1.0, 2.0, "s"),
        LogNormal(0.3, 0.4, "s"),
        LogNormal(0.3, 0.4, "s", upper=0.4),
        Taper(0.3, 1.8, 1.1, "s"),
    ],
)
def test_median_and_interval_agree_with_the_samples(prior):
    x = prior.sample(np.random.default_rng(0), 200_000)
    lo, hi = prior.interval(0.9)
    assert np.median(x) == pytest.approx(prior.median, rel=0.01)
    # Quantiles of a distribution that may have point masses (a cap, the prismatic taper).
    for q, level in ((lo, 0.05), (hi, 0.95)):
        assert np.mean(x < q) - 0.005 <= level <= np.mean(x <= q) + 0.005


def test_the_taper_has_a_point_mass_at_one():
    x = Taper(TAPER_PRISMATIC_SHARE, 1.8, 1.1, "s").sample(np.random.default_rng(0), 100_000)
    assert np.mean(x == 1.0) == pytest.approx(TAPER_PRISMATIC_SHARE, abs=0.01)
    assert x.min() > 0.0 and x.max() <= 1.0


def test_the_masonry_prior_is_a_labelled_judgement():
    prior = RegionPriors().masonry
    assert isinstance(prior, Categorical) and prior.judgement
    assert "judgement" in prior.source
    assert set(prior.categories) == set(BELL_TOWER_MASONRY_TYPES)
    assert "semi_solid_brick" not in prior.categories
    x = prior.sample(np.random.default_rng(0), 70_000)
    shares = [np.mean(x == k) for k in prior.categories]
    np.testing.assert_allclose(shares, 1 / 7, atol=0.01)
    assert len(prior.interval(0.9)) == 7
    assert "judgement" not in RegionPriors().wall_ratio.source  # TURRIS: data


def test_strength_and_weight_follow_table_c85i():
    for name, row in MASONRY_TYPES.items():
        fm = strength_prior(name)
        assert fm.interval(0.999999)[0] >= row.fm_min_pa - 1e-6
        assert fm.interval(0.999999)[1] <= row.fm_max_pa + 1e-6
        assert fm.median == pytest.approx(0.5 * (row.fm_min_pa + row.fm_max_pa))
    assert isinstance(strength_prior("roughly_cut_stone"), Point)
    assert unit_weight_prior("soft_stone").interval(0.999999) == pytest.approx((13e3, 16e3))
    assert unit_weight_prior("rubble").median == MASONRY_TYPES["rubble"].unit_weight_n_m3


def test_a_geometry_only_row_gets_the_region_priors():
    priors = TowerPriors.from_tower(TOWER)
    assert isinstance(priors.wall, LogNormal)
    assert priors.wall.median == pytest.approx(WALL_RATIO_MEDIAN * 5.0)
    assert priors.wall.interval(0.999999)[1] <= WALL_RATIO_MAX * 5.0
    assert priors.judgements == ("masonry_type",)
    s = priors.sample(np.random.default_rng(0), 500)
    assert set(s) == {
        "wall_m",
        "wall_top_m",
        "masonry_type",
        "fm_pa",
        "unit_weight_n_m3",
        "period_s",
    }
    assert all(len(v) == 500 for v in s.values())
    assert np.all(s["wall_top_m"] <= s["wall_m"])
    for name in BELL_TOWER_MASONRY_TYPES:
        row, mask = MASONRY_TYPES[name], s["masonry_type"] == name
        assert np.all((s["fm_pa"][mask] >= row.fm_min_pa) & (s["fm_pa"][mask] <= row.fm_max_pa))


def test_inventory_columns_collapse_their_priors():
    row = replace(
        TOWER,
        wall_thickness_m=1.2,
        wall_thickness_top_m=0.9,
        masonry_type="rubble",
        masonry_strength_mpa=1.7,
        knowledge_level="LC3",
        shaft_period_s=0.8,
    )
    priors = TowerPriors.from_tower(row)
    s = priors.sample(np.random.default_rng(0), 4)
    np.testing.assert_allclose(s["wall_m"], 1.2)
    np.testing.assert_allclose(s["wall_top_m"], 0.9)
    np.testing.assert_allclose(s["fm_pa"], 1.7e6)
    np.testing.assert_allclose(s["period_s"], 0.8)
    assert list(s["masonry_type"]) == ["rubble"] * 4
    assert priors.judgements == ()
    # A base wall without the top keeps the taper's prior (the row says nothing of it).
    assert isinstance(TowerPriors.from_tower(replace(row, wall_thickness_top_m=None)).taper, Taper)


def test_the_same_seed_gives_the_same_samples():
    priors = TowerPriors.from_tower(TOWER)
    a = priors.sample(np.random.default_rng(7), 50)
    b = priors.sample(np.random.default_rng(7), 50)
    c = priors.sample(np.random.default_rng(8), 50)
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])
    assert not np.array_equal(a["fm_pa"], c["fm_pa"])


GOOD = """
region = "test region"
[wall_ratio]
median = 0.25
log_std = 0.3
source = "survey"
[taper]
value = 1.0
source = "prismatic shafts of the region"
judgement = true
[masonry]
weights = { solid_brick = 0.75, rubble = 0.25 }
source = "Po valley"
[period_ratio]
median = 1.0
log_std = 0.2
source = "local identifications"
"""


def test_a_region_file_replaces_the_defaults(tmp_path):
    path = tmp_path / "priors.toml"
    path.write_text(GOOD)
    region = read_region_priors(path)
    assert region.wall_ratio == LogNormal(0.25, 0.3, "survey", upper=WALL_RATIO_MAX)
    assert region.taper == Point(1.0, "prismatic shafts of the region", True)
    assert region.masonry.categories == ("solid_brick", "rubble")
    priors = TowerPriors.from_tower(TOWER, region)
    assert priors.judgements == ("taper",)
    s = priors.sample(np.random.default_rng(0), 400)
    np.testing.assert_array_equal(s["wall_top_m"], s["wall_m"])
    assert set(s["masonry_type"]) == {"solid_brick", "rubble"}
    # A table the file lacks keeps the default.
    path.write_text('[taper]\nvalue = 0.5\nsource = "x"\n')
    assert read_region_priors(path).masonry == RegionPriors().masonry


@pytest.mark.parametrize(
    ("text", "key", "allowed"),
    [
        ('[wall]\nmedian = 0.2\nsource = "x"\n', "wall", "wall_ratio, taper"),
        (
            '[wall_ratio]\nmedian = 0.2\nlog_sd = 0.3\nsource = "x"\n',
            "[wall_ratio] log_sd",
            "median, log_std, source",
        ),
        (
            '[wall_ratio]\nmedian = 0.7\nlog_std = 0.3\nsource = "x"\n',
            "[wall_ratio] median",
            "a number in (0, 0.5]",
        ),
        ("[wall_ratio]\nmedian = 0.2\nlog_std = 0.3\n", "[wall_ratio] source", "a text"),
        (
            '[taper]\nprismatic_share = 1.5\nbeta_a = 1\nbeta_b = 1\nsource = "x"\n',
            "[taper] prismatic_share",
            "a number in [0, 1]",
        ),
        (
            '[masonry]\nweights = { brick = 1.0 }\nsource = "x"\n',
            "[masonry] weights.brick",
            "rubble, roughly_cut_stone",
        ),
        (
            '[masonry]\nweights = { rubble = 0.5 }\nsource = "x"\n',
            "[masonry] weights",
            "summing to 1",
        ),
        ('[masonry]\nvalue = "marble"\nsource = "x"\n', "[masonry] value", "solid_brick"),
        (
            '[period_ratio]\nvalue = "one"\nsource = "x"\n',
            "[period_ratio] value",
            "a number in [0.2, 5]",
        ),
        ('[taper]\nvalue = 1.0\nbeta_a = 2\nsource = "x"\n', "[taper] value", "one or the other"),
        ('[period_ratio]\nmedian = 1.0\nsource = "x"\n', "[period_ratio] log_std", "median"),
        (
            '[taper]\nvalue = 1.0\nsource = "x"\njudgement = "yes"\n',
            "[taper] judgement",
            "true, false",
        ),
        ("[belfry]\nsampled = 0\n", "[belfry] sampled", "true, false"),
        ("[belfry]\npresence = 0.5\n", "[belfry] source", "a text"),
        ('[belfry]\npresence = 1.5\nsource = "x"\n', "[belfry] presence", "[0, 1]"),
        ("[belfry]\nsampled = false\npresence = 0.5\n", "[belfry] presence", "one or"),
        ("[belfry]\nheight_share = 0.2\n", "[belfry] height_share", "sampled, presence"),
    ],
)
def test_a_bad_region_file_is_refused_naming_file_key_and_allowed(tmp_path, text, key, allowed):
    path = tmp_path / "priors.toml"
    path.write_text(text)
    with pytest.raises(ConfigError) as info:
        read_region_priors(path)
    message = str(info.value)
    assert str(path) in message and key in message and allowed in message
    assert "\n" not in message


def test_an_unreadable_region_file_is_refused(tmp_path):
    with pytest.raises(ConfigError, match="cannot read"):
        read_region_priors(tmp_path / "absent.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[taper\n")
    with pytest.raises(ConfigError, match="not valid TOML"):
        read_region_priors(bad)


def test_the_belfry_table_of_a_region_file(tmp_path):
    """Sampled by default; ``sampled = false`` turns it off; a region's presence, sourced."""
    assert RegionPriors().belfry == BelfryPriors()
    off = tmp_path / "off.toml"
    off.write_text("[belfry]\nsampled = false\n")
    assert read_region_priors(off).belfry is None
    mixed = tmp_path / "mixed.toml"
    mixed.write_text('[belfry]\npresence = 0.65\nsource = "civic towers too"\n')
    belfry = read_region_priors(mixed).belfry
    assert belfry.presence == 0.65 and belfry.sources["belfry_present"] == "civic towers too"
    assert "belfry_present" not in belfry.judgements  # judgement = false by default
    assert belfry.height_share == BelfryPriors().height_share
