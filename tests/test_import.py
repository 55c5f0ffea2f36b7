"""What importing rockstudy costs: the public API is imported on first use, jobs that simulate nothing
load neither numba nor the compiled model, and numba's cache folder is still set before any compiled
function is defined, whoever imports numba first."""
import pytest

import rockstudy
from fresh_python import run

LOADED = "import sys; print(sorted(m for m in ('numba', 'xarray', 'matplotlib') if m in sys.modules))"


def test_import_rockstudy_loads_neither_numba_nor_xarray():
    assert run(f"import rockstudy; {LOADED}") == "[]"


@pytest.mark.parametrize("imports", [
    "from rockstudy import report; from rockstudy.core import io",  # the report's HTML tables
    "from rockstudy.core import io; from rockstudy.studies import study, tables",  # Table 1, the timing tables
    "from rockstudy.core import io; from rockstudy.studies import claims, study",  # the claims checklist
    "from rockstudy.core import io; from rockstudy.studies import datasets, parameters, study",  # gathering
    "from rockstudy import plotting; from rockstudy.core import io; from rockstudy.studies import study",  # figures
])
def test_modules_of_jobs_that_simulate_nothing_do_not_load_numba(imports):
    assert "numba" not in run(f"{imports}; {LOADED}")


def test_a_jobs_parameters_unpickle_without_the_tables_dependencies():
    """Every job unpickles its parameters, some of them classes of :mod:`rockstudy.report.parameters`: that
    loads neither scipy, xarray nor the report's table modules (half a second a job when it did)."""
    code = ("import pickle, sys; from rockstudy.report.parameters import SourceFingerprint; "
            "pickle.loads(pickle.dumps(SourceFingerprint('abc', 'core'))); "
            "print(sorted(m for m in ('scipy', 'xarray', 'rockstudy.report.risk_table', 'rockstudy.report.overview')"
            " if m in sys.modules))")
    assert run(code) == "[]"


def test_every_name_of_the_report_package_is_there():
    from rockstudy import report
    namespace = {}
    exec("from rockstudy.report import *", namespace)
    assert set(report.__all__) <= set(namespace) and set(report.__all__) <= set(dir(report))
    with pytest.raises(AttributeError, match="no attribute 'nonesuch'"):
        report.nonesuch  # noqa: B018


@pytest.mark.parametrize("order", ["import rockstudy, numba", "import numba, rockstudy"])
def test_numba_caches_in_the_source_trees_folder_whoever_imports_numba_first(order):
    code = (f"{order}; from rockstudy.model import anchorage; "
            "print(numba.config.CACHE_DIR == rockstudy._numba_cache_dir(), "
            "anchorage.spring_right_intact._cache._cache_path.startswith(rockstudy._numba_cache_dir()))")
    assert run(code) == "True True"


def test_numba_cache_dir_in_the_environment_wins(tmp_path):
    code = "import rockstudy, numba; print(numba.config.CACHE_DIR)"
    assert run(code, NUMBA_CACHE_DIR=str(tmp_path)) == str(tmp_path)


def test_the_public_api_is_all_there():
    namespace = {}
    exec("from rockstudy import *", namespace)
    assert set(rockstudy.__all__) <= set(namespace)
    assert set(rockstudy.__all__) <= set(dir(rockstudy))
    from rockstudy.engine.simulate import simulate
    assert rockstudy.simulate is simulate and rockstudy.plotting.__name__ == "rockstudy.plotting"
    with pytest.raises(AttributeError, match="no_such_name"):
        rockstudy.no_such_name  # noqa: B018
