"""SIGINT (Ctrl-C) and SIGTERM in the package's command-line modules (``python3 -m
oscidrum.paper``, ``oscidrum.plot``, ``oscidrum.identify``, which the oscidrum tool runs): the
first one raises :class:`Interrupted` (a KeyboardInterrupt), later ones are ignored (the tool
passes on the signal a terminal also sent to the whole process group), and the module ends with
exit status 130 or 143 and one line on stderr, without a traceback."""

from __future__ import annotations

import contextlib
import signal
import sys
from typing import Callable, Iterator, Optional, Sequence

_SIGNALS = (signal.SIGINT, signal.SIGTERM)

#: The exit status of a module that printed why it failed (no data to plot, a bad file): the
#: oscidrum tool passes it on without suggesting that the package or matplotlib is missing.
EXIT_EXPLAINED = 3


class Interrupted(KeyboardInterrupt):
    """Raised by the first SIGINT or SIGTERM; `signum` says which."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _on_signal(signum: int, frame: object) -> None:
    for s in _SIGNALS:
        signal.signal(s, signal.SIG_IGN)
    raise Interrupted(signum)


def run_main(main: Callable[[Optional[Sequence[str]]], int], prog: str,
             argv: Optional[Sequence[str]] = None) -> int:
    """main(argv)'s exit status; 128 + the signal's number when SIGINT or SIGTERM stopped it.

    The oscidrum tool starts the modules through a bootstrap that ends them at once on a signal
    until they get here (and with the signals blocked until it runs); a module started so, or
    with the signals blocked otherwise, has them unblocked here, once the handlers are in
    place."""
    for s in _SIGNALS:
        signal.signal(s, _on_signal)
    try:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, set(_SIGNALS))
        return main(argv)
    except KeyboardInterrupt as exc:
        signum = getattr(exc, "signum", signal.SIGINT)
        print(f"{prog}: interrupted", file=sys.stderr)
        return 128 + int(signum)


@contextlib.contextmanager
def signals_deferred() -> Iterator[None]:
    """SIGINT and SIGTERM held back inside the block (moving finished files into place), and
    delivered when it ends."""
    old = signal.pthread_sigmask(signal.SIG_BLOCK, set(_SIGNALS))
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)
