"""Hazard files of OpenQuake, nshmp-haz and the USGS hazard tool (real files, tests/data/hazard/README.md),
read against hand conversions of their numbers."""
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from rockstudy.analysis.hazard import HazardFileError, parse_hazard_sites, read_hazard_curve, read_hazard_sites

DATA = Path(__file__).resolve().parents[1] / "data" / "hazard"


def test_openquake_newer_header_gives_every_site_as_annual_rates():
    sites = read_hazard_sites(DATA / "openquake-hazard_curve-mean_PGA.csv")
    assert [(s.lon, s.lat) for s in sites] == [(-122.34, 37.72), (-122.15, 37.56), (-119.33, 35.06), (-118.25, 34.05)]
    first = sites[0].curve
    # by hand: p = 9.537098E-02 in 50 years at 0.005 g -> -ln(1 - p)/50
    assert first.pga_g[0] == 0.005 and first.annual_rate[0] == pytest.approx(2.004606839508e-3, rel=1e-12)
    assert first.annual_rate[-1] == pytest.approx(-math.log(1 - 6.551776e-3) / 50, rel=1e-12)
    assert first.pga_g.size == 13 and sites[0].file_format == "openquake"
    # the third site's top level has p = 0: dropped and said
    assert sites[2].curve.pga_g[-1] == 0.203 and any("rate 0 dropped" in n for n in sites[2].notes)


def test_openquake_older_header_and_custom_site_ids():
    old = read_hazard_curve(DATA / "openquake-hazard_curve-mean.csv")
    np.testing.assert_allclose(old.pga_g, [0.1, 0.4, 0.6])
    np.testing.assert_allclose(old.annual_rate, -np.log1p(-np.array([1.067446e-2, 8.034880e-4, 9.711464e-5])),
                               rtol=1e-12)
    (site,) = read_hazard_sites(DATA / "openquake-hazard_curve-mean-PGA.csv")
    assert site.name == "7zzzzzzz" and site.curve.pga_g.tolist() == [0.1, 0.4]
    # one year: rate = -ln(1 - 0.994122) = 5.1365 /yr at 0.001 g, a plausible low level
    (busy,) = read_hazard_sites(DATA / "openquake-hazard_curve-mean-PGA-case10.csv")
    assert busy.curve.annual_rate[0] == pytest.approx(-math.log(1 - 9.941220e-1), rel=1e-12)


def test_a_probability_of_one_is_dropped_and_said_never_an_infinite_rate():
    text = (DATA / "openquake-hazard_curve-mean-PGA-case10.csv").read_text().replace("9.941220E-01", "1.000000E+00")
    (site,) = parse_hazard_sites(text, "edited.csv")  # the real file with its first probability set to 1
    assert site.curve.pga_g[0] == pytest.approx(0.0021544) and np.all(np.isfinite(site.curve.annual_rate))
    assert any("probability of exceedance 1" in n for n in site.notes)


def test_an_openquake_curve_of_another_im_is_refused_naming_it():
    with pytest.raises(HazardFileError, match=r"SA\(0.5\), not PGA"):
        read_hazard_sites(DATA / "openquake-hazard_curve-mean-SA(0.5).csv")


def test_nshmp_haz_curves_by_site_with_names_and_zero_rates_dropped():
    sites = read_hazard_sites(DATA / "nshmp-haz" / "PGA" / "total.csv")
    assert [s.name for s in sites][:3] == ["Concord CA", "Oakland CA", "San Francisco CA"] and len(sites) == 7
    oakland = sites[1]
    assert (oakland.lon, oakland.lat) == (-122.25, 37.8)
    assert oakland.curve.rate(0.103) == pytest.approx(1.28698458e-03, rel=1e-12)  # annual rates, as written
    assert oakland.curve.pga_g[-1] == 0.397 and any("6 level(s) from 0.556" in n for n in oakland.notes)


def test_nshmp_haz_curves_of_another_im_are_refused_by_their_folder(tmp_path):
    folder = tmp_path / "SA0P2"
    folder.mkdir()
    shutil.copy(DATA / "nshmp-haz" / "PGA" / "total.csv", folder / "total.csv")
    with pytest.raises(HazardFileError, match="SA0P2, not PGA"):
        read_hazard_sites(folder / "total.csv")


def test_usgs_hazard_tool_json_takes_the_pga_curve_among_three():
    (site,) = read_hazard_sites(DATA / "usgs-hazard-tool-curve.json")
    assert (site.lon, site.lat) == (-118.0, 34.0) and site.file_format == "usgs-json"
    assert site.curve.pga_g.size == 20 and site.curve.rate(0.103) == pytest.approx(0.020243, rel=1e-12)
    sa = (DATA / "usgs-hazard-tool-curve.json").read_text().replace('"PGA"', '"PGV"')
    with pytest.raises(HazardFileError, match="no PGA curve"):
        parse_hazard_sites(sa, "edited.json")


def test_a_curve_in_another_unit_is_refused_unless_stated():
    levels = np.array([0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0])
    rates = np.array([1.2e-1, 4e-2, 1.5e-2, 4e-3, 4.5e-4, 5e-5, 4e-6])
    for unit, per_g in (("m/s2", 9.80665), ("cm/s2", 980.665), ("%g", 100.0)):
        text = "".join(f"{float(x * per_g)!r} {float(r)!r}\n" for x, r in zip(levels, rates))
        with pytest.raises(HazardFileError, match="state it"):
            parse_hazard_sites(text, "site.txt")
        (site,) = parse_hazard_sites(text, "site.txt", unit=unit)
        np.testing.assert_allclose(site.curve.pga_g, levels, rtol=1e-12)
    with pytest.raises(ValueError, match="not a PGA unit"):
        parse_hazard_sites("0.1 1e-2\n0.2 1e-3\n", "site.txt", unit="furlong")


@pytest.mark.parametrize("text, words", [
    ("# investigation_time=50.0, imt='PGA'\nlon,lat,poe-0.1,poe-0.2\n0,0,0.5,1.5\n", ["line 3", "outside [0, 1]"]),
    ("# imt='PGA'\nlon,lat,poe-0.1,poe-0.2\n0,0,0.5,0.1\n", ["line 1", "investigation_time"]),
    ("# investigation_time=50.0\nlon,lat,poe-0.1,poe-0.2\n0,0,0.1,0.5\n", ["line 3", "rises"]),
    ("# investigation_time=50.0\nlon,lat,poe-0.1,poe-0.2\n0,0,0.1\n", ["line 3", "values for the header"]),
    ("name,lon,lat,0.1,0.2\nA,0,0,1e-3,0\n", ["line 2", "fewer than 2"]),
])
def test_bad_tool_files_name_the_line(text, words):
    with pytest.raises(HazardFileError) as err:
        parse_hazard_sites(text, "f.csv")
    message = str(err.value)
    assert message.startswith("f.csv") and all(w in message for w in words) and message.count("\n") < 3


def test_usgs_json_with_components_reads_the_total():
    """The newer service layout (``xvalues``, one ``yvalues`` per ``component``), made by editing the real file:
    the Total curve is read, whatever the other components hold."""
    import json
    doc = json.loads((DATA / "usgs-hazard-tool-curve.json").read_text())
    for response in doc["response"]:
        response["metadata"]["xvalues"] = response["metadata"].pop("xvals")
        total = response["data"][0]["yvals"]
        response["data"] = [{"component": "Fault", "yvalues": [v / 2 for v in total]},
                            {"component": "Total", "yvalues": total}]
    (site,) = parse_hazard_sites(json.dumps(doc), "edited.json")
    assert site.curve.rate(0.103) == pytest.approx(0.020243, rel=1e-12) and site.lon == -118.0
