"""Help that helps (issue 18, item 7): every command, positional argument and option has a help line,
each command's help ends with an example of itself, and `draw --help` says what each sheet and style is."""
import argparse

import pytest

from velpoly.cli import SHEET_HELP, SHEETS, STYLE_HELP, STYLES, build_parser


def _commands():
    p = build_parser()
    sub = next(a for a in p._actions if isinstance(a, argparse._SubParsersAction))
    return p, sub


def test_the_main_help_lists_every_command_with_a_line_and_ends_with_an_example():
    p, sub = _commands()
    helps = {a.dest: a.help for a in sub._choices_actions}
    assert set(helps) == set(sub.choices) and all(helps.values())
    text = p.format_help()
    assert text.rstrip().splitlines()[-1].strip().startswith("velpoly ") and "example:" in text


@pytest.mark.parametrize("name", sorted(_commands()[1].choices))
def test_every_argument_has_a_help_line_and_the_help_ends_with_an_example(name):
    cmd = _commands()[1].choices[name]
    for action in cmd._actions:
        assert action.help and action.help != argparse.SUPPRESS or isinstance(action, argparse._HelpAction), \
            (name, action.dest)
    text = cmd.format_help()
    last = text.rstrip().splitlines()
    assert last[-2].strip() == "example:" and last[-1].strip().startswith(f"velpoly {name}"), text


def test_draw_help_says_what_each_sheet_and_style_is():
    text = _commands()[1].choices["draw"].format_help()
    for k in SHEETS:
        assert k in SHEET_HELP and f"  {k:<13} {SHEET_HELP[k]}" in text
    for k in STYLES:
        assert f"  {k:<13} {STYLE_HELP[k]}" in text
