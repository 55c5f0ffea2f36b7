"""The generated pages of the documentation: the command-line reference (docs/cli.md, from the parser), the
API pages (one per module, its summary once), the gallery and the changelog page."""
import argparse
import importlib.util
import re
from pathlib import Path

from rockstudy.cli import build_parser
from rockstudy.cli.reference import command_reference

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def test_the_committed_reference_is_the_parsers():
    """docs/cli.md is what the documentation build writes from today's parser (a new option shows up there)."""
    assert (DOCS / "cli.md").read_text(encoding="utf-8") == command_reference(build_parser())


def test_the_reference_lists_every_option_of_every_command_with_its_default():
    parser = build_parser()
    text = command_reference(parser)
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, command in sub.choices.items():
        section = text.split(f"## `rockstudy {name}`", 1)[1].split("\n## ", 1)[0]
        for action in command._actions:
            for option in action.option_strings:
                if option not in ("-h", "--help"):
                    assert f"`{option}`" in section, (name, option)
    assert "| `--strategy` `{FS,PASSIVE,CS01,CS02}` | control strategy (default CS01) |" in text
    assert "%(default)" not in text


def _conf():
    spec = importlib.util.spec_from_file_location("docs_conf", DOCS / "conf.py")
    conf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conf)
    return conf


def test_each_api_page_prints_its_modules_summary_once(tmp_path, monkeypatch):
    conf = _conf()
    monkeypatch.setattr(conf, "MODULE_PAGES", tmp_path)
    conf._write_module_pages(None)
    pages = sorted(tmp_path.glob("*.md"))
    assert len(pages) == len(conf.public_modules()) > 50
    for page in pages:  # the page holds the title and the automodule, which prints the docstring (summary first)
        body = page.read_text(encoding="utf-8")
        assert re.fullmatch(r"# `[\w.]+`\n\n```\{eval-rst\}\n\.\. automodule:: [\w.]+\n```\n", body), page.name


def test_intersphinx_fetches_nothing_offline(monkeypatch):
    monkeypatch.delenv("ROCKSTUDY_DOCS_ONLINE", raising=False)
    assert _conf().intersphinx_mapping == {}
    monkeypatch.setenv("ROCKSTUDY_DOCS_ONLINE", "1")
    assert set(_conf().intersphinx_mapping) == {"python", "numpy", "scipy", "xarray"}


def test_the_gallery_shows_every_figure_of_the_docs():
    gallery = (DOCS / "gallery.md").read_text(encoding="utf-8")
    shown = set(re.findall(r"```\{figure\} figures/(\S+)", gallery))
    assert shown == {p.name for p in (DOCS / "figures").glob("*.png")}
    refreshed = re.findall(r'"([\w.-]+\.png)"', (ROOT / "workflow" / "rules" / "docs.smk").read_text())
    assert set(refreshed) <= shown and len(refreshed) >= 6  # `snakemake docs` refreshes them from the run


def test_the_changelog_is_a_page():
    assert "{include} ../CHANGELOG.md" in (DOCS / "changelog.md").read_text(encoding="utf-8")
    assert "changelog" in (DOCS / "index.md").read_text(encoding="utf-8")
