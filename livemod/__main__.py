"""``python -m livemod`` is the ``livemod`` command."""

from livemod.cli import main

raise SystemExit(main())
