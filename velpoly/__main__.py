import sys

try:
    from .cli import main
except KeyboardInterrupt:   # Ctrl-C while Python is still importing: no traceback (FORMAT.md section 3)
    sys.stderr.write("error: interrupted\n")
    sys.unraisablehook = lambda u: None   # half-built objects of the stopped import fail in __del__: no news
    exec("pass", {})   # CPython's note of an unhandled Ctrl-C cleared (velpoly.cli._forget_unhandled_interrupt)
    sys.exit(130)

sys.exit(main())
