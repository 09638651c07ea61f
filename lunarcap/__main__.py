"""``python -m lunarcap``: the command-line interface."""

from lunarcap.cli import main

raise SystemExit(main())
