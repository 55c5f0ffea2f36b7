"""The IOOS compliance checker (CF 1.11) on one netCDF file: its high-priority findings."""
import warnings

CF_SUITE = "cf:1.11"


def high_priority_findings(path) -> list[str]:
    """Messages of the failed high-priority CF checks of ``path`` (every one of them: none is allowed)."""
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
            found += [f"{result.name}: {m}" for m in result.msgs]
    return found
