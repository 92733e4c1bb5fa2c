"""Pages generated from the code at every build: the config reference (from the schema), the
command-line reference (from the argparse parser) and the API pages (one per subpackage, from the
docstrings).  Written only when their text changes, so Sphinx rebuilds only what moved."""
import argparse
import importlib
import pkgutil
from pathlib import Path

SUBPACKAGES = ("geometry", "fem", "mbs", "bearing", "pipelines")


def _write(path: Path, text: str) -> None:
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def config_page() -> str:
    from axlebox.pipelines.config_reference import reference_markdown
    return reference_markdown()


def _subcommands(p: argparse.ArgumentParser, prefix: str):
    """(command line, parser) for every leaf of the parser's sub-command tree, in order."""
    subs = [a for a in p._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield prefix, p
        return
    for name, sp in subs[0].choices.items():
        yield from _subcommands(sp, f"{prefix} {name}")


def cli_page() -> str:
    from axlebox.pipelines.cli import parser
    p = parser()
    out = ["# Command-line reference", "",
           "Generated from the `axlebox` command's own parser (`axlebox.pipelines.cli.parser`), "
           "so each option's name, default and help are what the installed command accepts.  "
           "Exit status 0 on success, 2 on bad input (one line naming the field, the value and "
           "what is allowed), 1 on a failed computation.", ""]
    for line, sp in _subcommands(p, "axlebox"):
        sp.prog = line
        out += [f"## `{line}`", "", "```text", sp.format_help().rstrip(), "```", ""]
    return "\n".join(out)


def modules(sub: str) -> list[str]:
    pkg = importlib.import_module(f"axlebox.{sub}")
    names = [pkg.__name__] + [m.name for m in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + ".")]
    return [n for n in names if not n.rsplit(".", 1)[-1].startswith("_")]


def api_pages(folder: Path) -> None:
    folder.mkdir(exist_ok=True)
    index = ["# API reference", "",
             "One page per subpackage, from the docstrings.  Data flows one way: geometry -> fem "
             "-> (reduced-body files) -> mbs <- bearing, with pipelines on top.", "",
             "```{toctree}", ":maxdepth: 1", ""] + list(SUBPACKAGES) + ["```", ""]
    _write(folder / "index.md", "\n".join(index))
    for sub in SUBPACKAGES:
        text = [f"# axlebox.{sub}", ""]
        for name in modules(sub):
            text += [f"## {name}", "", "```{eval-rst}", f".. automodule:: {name}", "```", ""]
        _write(folder / f"{sub}.md", "\n".join(text))


def write_all(folder: Path) -> None:
    folder.mkdir(exist_ok=True)
    _write(folder / "cli.md", cli_page())
    _write(folder / "config.md", config_page())
    api_pages(folder / "api")
