"""The command-line forms the figure scripts share."""
import sys


def labelled(arguments, usage):
    """[(label, value)] of LABEL=VALUE arguments, split at the last '=' (a label may hold one, as in
    'alpha = 0.5=runs/...'); exits with `usage` when an argument has none or there are none."""
    if not arguments or any("=" not in argument for argument in arguments):
        sys.exit(usage)
    return [tuple(argument.rsplit("=", 1)) for argument in arguments]


def output_and_labelled(arguments, usage):
    """(OUTPUT, [(label, value)]) of the arguments OUTPUT LABEL=VALUE [LABEL=VALUE ...]."""
    if len(arguments) < 2:
        sys.exit(usage)
    return arguments[0], labelled(arguments[1:], usage)


def dispatch(commands, usage, argv):
    """Runs commands[argv[0]](argv[1:]), a family script's subcommand; exits with `usage` for an unknown one."""
    if not argv or argv[0] not in commands:
        sys.exit(usage)
    commands[argv[0]](argv[1:])
