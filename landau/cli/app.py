"""The ``landau`` command line.

Each sub-command lives in its own module exposing ``configure(parser)``,
``run(args) -> dict`` (the JSON document) and ``render(doc) -> str`` (the human
table).  This module only wires them up and enforces the contract: ``--json`` prints
one JSON document on stdout; bad input exits with code 2 and a one-line message on
stderr naming what is wrong.
"""

from __future__ import annotations

import argparse
import difflib
import importlib
import importlib.util
import json
import math
import numbers
import os
import re
import sys
from typing import Any, Sequence

from landau.errors import InputError, LandauError

#: sub-command -> module implementing it
COMMANDS: dict[str, str] = {
    "linear": "landau.cli.linear",
    "derive": "landau.cli.derive",
    "scene": "landau.cli.scene",
    "laws": "landau.cli.laws",
    "transition": "landau.cli.transition",
    "plot": "landau.cli.plot",
    "simulate": "landau.cli.simulate",
    "hopf": "landau.cli.hopf",
    "cycles": "landau.cli.cycles",
    "nucleation": "landau.cli.nucleation",
    "sweep": "landau.cli.sweep",
    "sweep-merge": "landau.cli.sweep_merge",
    "fit": "landau.cli.fit",
    "figures": "landau.paper_figures.cli",
    "verify": "landau.verify.cli",
}

#: what ``landau --help`` says first
DESCRIPTION = ("Weakly nonlinear analysis of friction-driven oscillators: stability thresholds, amplitude "
               "equations, simulations and the papers' published values.  Every command takes --json (one "
               "JSON document on stdout); bad input exits with code 2 and one line naming what is wrong.")

#: sub-command -> its one-line summary (the first line of its module's docstring, which a test
#: keeps in step), so that ``landau --help`` lists the commands without importing any of them
SUMMARIES: dict[str, str] = {
    "linear": "Linear stability of steady sliding: critical stiffness k_c (eq. 7) and frequency ω_c (eq. 8).",
    "derive": "Amplitude equation of the stick–slip Hopf bifurcation: Γ̄, Ω̄, Λ, χ, C (Putelat et al. 2010, "
              "eqs 15–23).",
    "scene": "Named, reproducible computations: landau scene list | landau scene run NAME|GLOB... [--all] "
             "[--param K=V ...].",
    "laws": "List the built-in friction laws with their equations, parameters and sources.",
    "transition": "Transition velocity V*(p) where the Hopf bifurcation changes nature, and the critical p*",
    "plot": "Plot a law's amplitude-equation coefficients against V, or its regime diagram, to a file.",
    "simulate": "Simulate one of the toolkit's models and write its time series (CSV, NPZ) or a plot (PNG).",
    "hopf": "Hopf point of a model's steady state, with its first Lyapunov coefficient and criticality.",
    "cycles": "Continue the branch of cycles of a model from its Hopf point, with Floquet multipliers and LPC/PD/NS "
              "points.",
    "nucleation": "The continuum fault's length scales: h*, L_b, the Rubin–Ampuero lengths and a patch's stiffness.",
    "figures": "Regenerate a paper's figures: landau figures PAPER [--only figN,...] [--out DIR].",
    "verify": "Check the engine's amplitude-equation predictions by direct simulation of the spring–block.",
    "sweep": "Run an analysis over a parameter grid on local processes or a dask cluster, written to netCDF.",
    "sweep-merge": "Join the shards of a sweep (landau sweep --shard I/N) into one netCDF file.",
    "fit": "Fit a friction law's parameters to a laboratory record (velocity steps, slide-hold-slide) by least "
           "squares.",
}


#: commands whose answer is a function of their arguments and of the code alone: a repeated call
#: prints the stored answer without importing sympy (:mod:`landau.support.answers`), except with one
#: of the options listed (they write files), when the command always runs.  ``verify`` is not among
#: them: its verdict is evidence from a simulation run now (a user's CI runs it to prove the numbers),
#: so a repeated ``verify`` simulates again
ANSWERED_FROM_STORE: dict[str, tuple[str, ...]] = {"hopf": (), "derive": ("--latex",), "linear": ("--latex",)}


def _answerable(argv: list[str]) -> bool:
    """Whether ``argv`` names a command of :data:`ANSWERED_FROM_STORE` without any of its
    file-writing options (nor an abbreviation of one, which argparse accepts)."""
    if not argv or argv[0] not in ANSWERED_FROM_STORE:
        return False
    refused = ANSWERED_FROM_STORE[argv[0]]
    for tok in argv[1:]:
        name = tok.split("=", 1)[0]
        if len(name) > 2 and name.startswith("--") and any(opt.startswith(name) for opt in refused):
            return False
    return True


class _Parser(argparse.ArgumentParser):
    """argparse that raises instead of exiting, so every bad input becomes exit 2 with one line."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise InputError(f"{self.prog}: {message}")


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return (text.splitlines()[0] if text else type(exc).__name__)[:500]


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    if isinstance(obj, numbers.Integral):
        return int(obj)
    try:
        x = float(obj)
    except (TypeError, ValueError):
        return str(obj)
    return x if math.isfinite(x) else None


def _version() -> str:
    from landau import __version__

    return __version__


class _VersionAction(argparse.Action):
    """``--version``: the installed version, looked up only when asked for."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings=option_strings, dest=dest, default=default, nargs=0,
                         help=help or "show the version and exit")

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"landau {_version()}")
        parser.exit()


#: a Sphinx cross-reference role, :role:`target` or :role:`~a.b.target` or :role:`text <target>`
_ROLE = re.compile(r":(?:py:)?[a-z]+:`(~?)([^`]+)`")
#: a reStructuredText inline literal, ``text`` (it may wrap onto the next line)
_LITERAL = re.compile(r"``(.+?)``", re.S)
#: a substitution reference, |name| (not a pipe between words: up|down|both)
_SUBSTITUTION = re.compile(r"(?<![\w|])\|(\w[\w-]*)\|(?![\w|])")
#: "paragraph::" or "paragraph: ::" introducing a literal block, and "::" on a line of its own
_BLOCK_MARKER = re.compile(r"(?<=\S)( ?)::[ \t]*$", re.M)
_BLOCK_MARKER_ALONE = re.compile(r"^[ \t]*::[ \t]*\n", re.M)


def _role_text(match: re.Match) -> str:
    short, target = match.group(1), match.group(2)
    if target.endswith(">") and "<" in target:  # :ref:`text <target>`
        return target[: target.index("<")].strip()
    return target.rsplit(".", 1)[-1] if short else target


def plain_text(doc: str) -> str:
    """A docstring as help text: its reStructuredText markup turned into plain text.

    A role gives its target (":func:`landau.check`" -> "landau.check", ":class:`~a.b.C`" -> "C"),
    an inline literal or a substitution its text ("``x``" -> "x", "|x|" -> "x"), and a paragraph
    that introduces a literal block ends with one colon ("Examples::" -> "Examples:").
    """
    doc = _ROLE.sub(_role_text, doc)
    doc = _LITERAL.sub(r"\1", doc)
    doc = _SUBSTITUTION.sub(r"\1", doc)
    doc = _BLOCK_MARKER_ALONE.sub("", doc)
    return _BLOCK_MARKER.sub(lambda m: "" if m.group(1) else ":", doc)


def _summary(modname: str) -> str | None:
    """The first line of a sub-command module's docstring (imports the module)."""
    doc = plain_text(importlib.import_module(modname).__doc__ or "").strip()
    return doc.splitlines()[0] if doc else None


def build_parser(only: str | None = None) -> tuple[argparse.ArgumentParser, dict[str, Any]]:
    """The argument parser.

    With ``only`` a command name, just that sub-command's module is imported (fast start); with
    ``only=""`` none is (``landau --help`` lists the commands by their :data:`SUMMARIES`).
    """
    parser = _Parser(prog="landau", description=DESCRIPTION,
                     epilog="`landau COMMAND --help` documents a command; `landau` alone runs `landau derive "
                            "dieterich` at four driving velocities.")
    parser.add_argument("--version", action=_VersionAction)
    sub = parser.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")
    modules: dict[str, Any] = {}
    for name, modname in COMMANDS.items():
        if only is not None and name != only:
            summary = SUMMARIES.get(name) if only == "" else None
            if only == "" and summary is None:  # a command without a summary: its docstring
                summary = _summary(modname)
            sub.add_parser(name, help=summary)
            continue
        if importlib.util.find_spec(modname.rsplit(".", 1)[0]) is None:
            continue
        try:
            spec = importlib.util.find_spec(modname)
        except ModuleNotFoundError:
            spec = None
        if spec is None:
            continue
        mod = importlib.import_module(modname)
        doc = plain_text(mod.__doc__) if mod.__doc__ else None  # help prints no reStructuredText markup
        p = sub.add_parser(name, help=doc.strip().splitlines()[0] if doc else None,
                           description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
        p.add_argument("--json", action="store_true", help="print one JSON document on stdout")
        mod.configure(p)
        modules[name] = mod
    return parser, modules


#: a negative number in exponent notation ("-1e-3"), or a list or range starting with one ("-1:1"),
#: which argparse would read as an option
_NEGATIVE_NUMBER = re.compile(r"-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?([,:].*)?")


def _join_negative_values(argv: list[str]) -> list[str]:
    """``--eps2 -1e-3`` → ``--eps2=-1e-3``: a value that looks like a negative number is the
    option's value (it is then checked, and refused, as a value), never a new option."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        tok = argv[i]
        if (tok.startswith("--") and "=" not in tok and i + 1 < len(argv)
                and _NEGATIVE_NUMBER.fullmatch(argv[i + 1])):
            out.append(f"{tok}={argv[i + 1]}")
            i += 2
            continue
        out.append(tok)
        i += 1
    return out


def _did_you_mean(word: str, choices) -> str:
    close = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    as_json = "--json" in argv
    try:
        return _main(argv, as_json)
    except KeyboardInterrupt:
        return _fail(as_json, 130, "Interrupted", "interrupted", "landau: interrupted")


def _fail(as_json: bool, code: int, kind: str, message: str, line: str) -> int:
    """Report an error: its one line on stderr and, with ``--json``, one JSON document on stdout
    (``{"error": ..., "kind": ..., "exit_code": ...}``); returns the exit code."""
    print(line, file=sys.stderr)
    if as_json:
        try:
            json.dump({"error": message, "kind": kind, "exit_code": code}, sys.stdout, indent=1)
            sys.stdout.write("\n")
            sys.stdout.flush()
        except (BrokenPipeError, ValueError):   # a closed stdout: the line on stderr says it
            pass
    return code


def _print_stored(code: int, text: str) -> int:
    """Print a stored answer (:mod:`landau.support.answers`) as the command printed it."""
    try:
        sys.stdout.write(text)
        sys.stdout.flush()
    except BrokenPipeError:
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError, AttributeError):
            pass
        return 1
    return code


def _main(argv: list[str], as_json: bool = False) -> int:
    if any(not isinstance(a, str) for a in argv):
        return _fail(as_json, 2, "InputError", "every argument must be a string",
                     "landau: error: every argument must be a string")
    argv = _join_negative_values(argv)
    try:
        if argv and not argv[0].startswith("-") and argv[0] not in COMMANDS:
            raise InputError(f"unknown command {argv[0]!r}{_did_you_mean(argv[0], COMMANDS)} "
                             f"(commands: {', '.join(COMMANDS)})")
        if argv in (["--version"], ["-V"]):
            print(f"landau {_version()}")
            return 0
        if not argv:
            argv = ["derive", "dieterich", "--V", "1e-5,2.6e-5,1e-4,1e-3"]
        answerable = _answerable(argv)
        if answerable:
            from landau.support import answers

            stored = answers.load(argv[0], argv)
            if stored is not None:
                return _print_stored(*stored)
        # the command named (or none: `landau --help` imports no sub-command)
        parser, modules = build_parser(next((a for a in argv if a in COMMANDS), ""))
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return 2
        mod = modules[args.command]
        doc = mod.run(args)
    except InputError as exc:
        return _fail(as_json, 2, type(exc).__name__, _first_line(exc), f"landau: error: {_first_line(exc)}")
    except LandauError as exc:
        return _fail(as_json, 1, type(exc).__name__, _first_line(exc),
                     f"landau: {type(exc).__name__}: {_first_line(exc)}")
    except OSError as exc:
        # an output that cannot be written (a folder, a missing or read-only place, a full disk)
        where = f" {exc.filename}" if getattr(exc, "filename", None) else ""
        msg = f"cannot write{where}: {exc.strerror or exc}"
        return _fail(as_json, 2, "OutputError", msg, f"landau: error: {msg}")
    except RecursionError:
        msg = "the input is too deeply nested (RecursionError)"
        return _fail(as_json, 2, "InputError", msg, f"landau: error: {msg}")
    except MemoryError:
        # a memory limit (ulimit -v, a container) or a computation too large for this machine: not the input's size
        msg = ("out of memory (MemoryError): the computation needs more memory than this process may use; "
               "raise the memory limit or ask for fewer points")
        return _fail(as_json, 2, "MemoryError", msg, f"landau: error: {msg}")
    except KeyboardInterrupt:
        raise
    except Exception as exc:  # noqa: BLE001 - the CLI promises one line, never a traceback
        msg = f"{type(exc).__name__}: {_first_line(exc)} (please report this with the command line)"
        return _fail(as_json, 1, "InternalError", msg, f"landau: internal error: {msg}")
    try:
        if getattr(args, "json", False):
            text = json.dumps(_jsonable(doc), indent=1, allow_nan=False) + "\n"
        else:
            text = mod.render(doc)
            text = text if text.endswith("\n") else text + "\n"
        sys.stdout.write(text)
        sys.stdout.flush()
    except BrokenPipeError:
        # the reader (e.g. `| head`) closed the pipe: stop quietly, as Unix tools do
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError, AttributeError):  # stdout without a file descriptor (captured)
            pass
        return 1
    except (ValueError, TypeError) as exc:  # a result the renderer cannot print: one line, never a traceback
        msg = f"{type(exc).__name__}: {_first_line(exc)} (please report this with the command line)"
        return _fail(as_json, 1, "InternalError", msg, f"landau: internal error: {msg}")
    code = int(doc.get("exit_code", 0)) if isinstance(doc, dict) else 0
    if answerable and code == 0:
        from landau.support import answers

        answers.store(argv[0], argv, code, text)
    if code and isinstance(doc, dict) and doc.get("failure"):   # a run that did not work says why on stderr
        sys.stderr.write(f"landau: {doc['failure']}\n")
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
