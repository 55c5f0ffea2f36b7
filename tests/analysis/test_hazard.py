"""Hazard curves: log-log interpolation, its inverse, and the hazard file reader's checks."""
import numpy as np
import pytest

from rockstudy.analysis.hazard import HazardCurve, HazardFileError, parse_hazard_text, read_hazard_curve


def test_loglog_interpolation_is_exact_for_a_power_law_and_inverts():
    x = np.array([0.01, 0.1, 1.0])
    curve = HazardCurve(x, 1e-4 * x ** -2.0)
    np.testing.assert_allclose(curve.slopes, [2.0, 2.0], rtol=1e-12)
    np.testing.assert_allclose(curve.rate([0.001, 0.05, 3.0]), 1e-4 * np.array([0.001, 0.05, 3.0]) ** -2.0,
                               rtol=1e-12)
    assert curve.pga_at_rate(1e-4 * 0.3 ** -2.0) == pytest.approx(0.3, rel=1e-12)


def test_hazard_file_comma_or_spaces_with_comments(tmp_path):
    path = tmp_path / "site.txt"
    path.write_text("# PGA [g], annual rate [1/yr]\n0.01, 2e-2\n\n0.1 3e-3  # a comment\n1.0\t1e-5\n")
    curve = read_hazard_curve(path, "site")
    np.testing.assert_array_equal(curve.pga_g, [0.01, 0.1, 1.0])
    np.testing.assert_array_equal(curve.annual_rate, [2e-2, 3e-3, 1e-5])
    assert curve.source == str(path)


@pytest.mark.parametrize("text, words", [
    ("0.01 1e-2\n0.1 2e-2\n", ["line 2", "rises above"]),
    ("0.1 1e-2\n0.01 1e-3\n", ["line 2", "does not rise"]),
    ("# header\n0.1 1e-2 7\n", ["line 2", "not two positive numbers"]),
    ("0.1 abc\n", ["line 1", "not two positive numbers"]),
    ("0.1 -1e-2\n", ["line 1"]),
    ("0.1 1e-2\n", ["at least 2 points"]),
])
def test_bad_hazard_files_name_the_line(text, words):
    with pytest.raises(HazardFileError) as err:
        parse_hazard_text(text, "site.txt")
    assert str(err.value).startswith("site.txt") and all(w in str(err.value) for w in words)


def test_missing_file_is_refused(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        read_hazard_curve(tmp_path / "nowhere.txt")


def test_a_flat_segment_is_a_curve_with_no_motion_between_its_levels():
    """nshmp-haz curves hold one rate over their lowest levels: a slope of 0, integrable and invertible (to
    the highest level of that rate)."""
    curve = HazardCurve([0.005, 0.01, 0.1, 1.0], [3e-3, 3e-3, 1e-3, 1e-5])
    assert curve.slopes[0] == 0.0 and curve.rate(0.007) == pytest.approx(3e-3, rel=1e-12)
    assert curve.pga_at_rate(3e-3) == 0.01 and curve.pga_at_rate(1e-4) == pytest.approx(10 ** -0.5, rel=1e-12)
    with pytest.raises(ValueError, match="must not rise"):
        HazardCurve([0.01, 0.1], [1e-3, 2e-3])
