"""``python -m rockstudy.cli``: the command line."""
import sys

from rockstudy.cli import main

sys.exit(main())
