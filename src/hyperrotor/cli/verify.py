"""``hyperrotor verify``: the preprint checked equation by equation (:mod:`hyperrotor.paper.verify`)."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from hyperrotor.cli._common import UsageError, add_common, bar, check_common
from hyperrotor.cli._files import Outputs, output_file

__all__ = ["configure", "run"]


_VERIFY_SUFFIXES = {"json": (".json",), "markdown": (".md", ".markdown"), "table": (".txt", ".text")}


def configure(p: argparse.ArgumentParser) -> None:
    """The options of ``hyperrotor verify`` (the section keys come from a module without SymPy: building
    the parser of any subcommand loads no heavy library)."""
    from hyperrotor.paper.section_titles import SECTION_TITLES

    fmt = p.add_mutually_exclusive_group()
    fmt.add_argument("--json", action="store_true", help="JSON list of {equation, status, detail, ...}")
    fmt.add_argument("--markdown", action="store_true", help="Markdown report (docs/verification.md)")
    p.add_argument("--section", action="append", choices=list(SECTION_TITLES), metavar="NAME",
                   help="only this section (repeatable); one of: " + ", ".join(SECTION_TITLES))
    p.add_argument("--output", "-o", metavar="FILE",
                   help="write the report to FILE instead of stdout: .txt (table), .md (Markdown) or .json; "
                        "without --json/--markdown the extension chooses the format, with them it must match")
    add_common(p)


def run(args: argparse.Namespace) -> int:
    from hyperrotor.paper.verify import SECTIONS, render, verify

    check_common(args)
    kind = "json" if args.json else "markdown" if args.markdown else None
    if kind is None and args.output is not None:  # no format option: the extension of --output chooses
        suffix = Path(args.output).suffix.lower()
        kind = next((k for k, sfx in _VERIFY_SUFFIXES.items() if suffix in sfx), "table")
    kind = kind or "table"
    keys = list(dict.fromkeys(args.section)) if args.section else list(SECTIONS)  # (a repeated --section: once)
    with Outputs() as outs:
        out = None
        if args.output is not None:
            flag = {"json": "--json", "markdown": "--markdown", "table": "no format option"}[kind]
            suffixes = _VERIFY_SUFFIXES[kind] if (args.json or args.markdown) else sum(_VERIFY_SUFFIXES.values(), ())
            try:
                out = outs.add(output_file(args.output, option="--output", suffixes=suffixes, force=args.force))
            except ValueError as err:
                msg = str(err)
                if (args.json or args.markdown) and ("has extension" in msg or "has no extension" in msg):
                    msg += f" (the {kind} report, {flag})"
                raise UsageError(msg) from None
        verdicts = []
        with bar(args, len(keys), "verify: sections", "section") as pbar:
            for key in keys:
                pbar.set_postfix_str(key)
                verdicts.extend(verify([key]))
                pbar.update()
        text = render(verdicts, format=kind)
        if out is None:
            # one write of the whole report (print wrote the text, then "\n": a reader that leaves after the first
            # line, `| head -1`, could close the pipe between the two, and the second write ended in status 141)
            sys.stdout.write(text + "\n")
            sys.stdout.flush()
            return 0
        out.tmp.write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8")
        outs.commit()
    print(f"written: {out.path} ({len(verdicts)} items)")
    return 0
