"""The IOOS compliance checker (CF 1.11) on one netCDF file: its high-priority findings."""
import re
import warnings

CF_SUITE = "cf:1.11"

ELAPSED_TIME = re.compile(r"Coordinate variable '(time|ground_time)' should have standard_name='time'")
"""The one high-priority finding allowed: a dimension named ``time`` asks for ``standard_name =
"time"``, which in turn asks for calendar units ("seconds since <epoch>"). rockstudy's ``time`` is
elapsed time since the start of the ground motion in plain seconds, so that ``ds.sel(time=2.0)``
works on the file as opened by xarray (calendar units would decode it to dates)."""


def high_priority_findings(path, allowed=ELAPSED_TIME) -> list[str]:
    """Messages of the failed high-priority CF checks of ``path`` (those matching ``allowed`` left out)."""
    from compliance_checker.base import BaseCheck
    from compliance_checker.runner import CheckSuite

    suite = CheckSuite()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        suite.load_all_available_checkers()
        results = suite.run_all(suite.load_dataset(str(path)), [CF_SUITE], skip_checks=[])[CF_SUITE][0]
    found = []
    for result in results:
        if result.weight != BaseCheck.HIGH or result.value is None:
            continue
        value = result.value
        passed = value[0] == value[1] if isinstance(value, tuple) else bool(value)
        if not passed:
            found += [f"{result.name}: {m}" for m in result.msgs if not (allowed and allowed.search(m))]
    return found
