import sys

try:
    from .cli import main
except KeyboardInterrupt:   # Ctrl-C while Python is still importing: no traceback (FORMAT.md section 3)
    sys.stderr.write("error: interrupted\n")
    sys.exit(130)

sys.exit(main())
