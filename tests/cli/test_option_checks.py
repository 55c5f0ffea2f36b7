"""The command line calls each of the library's checks once, naming its options."""
import json

import pytest

from rockstudy.cli import main
from rockstudy.core import quantities, validation

TINY = ["--frequency-start", "1", "--frequency-stop", "2", "--frequency-step", "1", "--min-amplitude-ratio", "0.9",
        "--max-amplitude-ratio", "1.5", "--amplitude-step", "0.3", "--resolution", "0.3"]


def _count(monkeypatch, module, name):
    calls = []
    real = getattr(module, name)

    def counted(*args, **kwargs):
        calls.append((args, kwargs))
        return real(*args, **kwargs)
    monkeypatch.setattr(module, name, counted)
    return calls


def test_spectrum_checks_the_amplitude_grid_once(tmp_path, monkeypatch, capsys):
    grids = _count(monkeypatch, validation, "check_amplitude_grid")
    frequencies = _count(monkeypatch, validation, "check_grid")
    fields = []
    real = quantities.Quantity.check

    def counted(self, name, value):
        fields.append(name)
        return real(self, name, value)
    monkeypatch.setattr(quantities.Quantity, "check", counted)
    main(["spectrum", "--strategy", "FS", "--output", str(tmp_path / "s.nc")] + TINY)
    assert json.loads(capsys.readouterr().out)["frequencies"] == 2
    grids = [call for call in grids if call[0] == (0.9, 1.5, 0.3, 0.3)]  # not the defaults made at import
    assert len(grids) == 1 and grids[0][1]["names"] == ("--min-amplitude-ratio", "--max-amplitude-ratio",
                                                        "--amplitude-step", "--resolution")
    for option in ("--min-amplitude-ratio", "--max-amplitude-ratio", "--amplitude-step", "--resolution",
                   "--frequency-start", "--frequency-stop", "--frequency-step"):
        assert fields.count(option) == 1, option
    assert [kw["names"] for args, kw in frequencies if args[1:4] == (1.0, 2.0, 1.0)] == [  # the frequency grid
        ("--frequency-start", "--frequency-stop", "--frequency-step")]


@pytest.mark.parametrize("option,value,needle", [
    ("--resolution", "0.5", "--resolution = 0.5 is not allowed: it must not exceed --amplitude-step"),
    ("--max-amplitude-ratio", "0.5", "--max-amplitude-ratio"),
    ("--amplitude-step", "-1", "--amplitude-step"),
    ("--frequency-step", "0", "--frequency-step"),
    ("--frequency-stop", "0.5", "--frequency-stop"),
])
def test_grid_errors_name_the_option(option, value, needle, tmp_path, capsys):
    args = ["spectrum", "--output", str(tmp_path / "s.nc")] + TINY + [option, value]
    with pytest.raises(SystemExit) as exc:
        main(args)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert needle in err and "AmplitudeGrid" not in err and "Traceback" not in err
    assert len(err.strip().splitlines()) <= 3
    assert not (tmp_path / "s.nc").exists()
