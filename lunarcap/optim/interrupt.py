"""CasADi's long calls off the main thread, so that Ctrl-C acts at once.

Python runs a signal handler in the main thread between bytecodes, so Ctrl-C during one
long C++ call (compiling an NLP with ``ca.nlpsol``: 5-15 s in full dynamics; an IPOPT
solve) acted only once the call returned. :func:`off_main_thread` runs such a call in a
daemon thread while the main thread waits, waking every :data:`POLL_S`; on Ctrl-C the main
thread raises KeyboardInterrupt at once and the call is abandoned, and :func:`busy` tells
the command line to leave with ``os._exit`` instead of waiting for it (or tearing C++ down
under it). CasADi releases the GIL in these calls, so the waiting main thread runs.

Called from any other thread (a Dask worker's task, a thread of :func:`map_in_threads`)
the call runs in place.
"""

from __future__ import annotations

import threading

#: One event per thread of :func:`map_in_threads`, set when it ends (``Thread.is_alive``
#: is not used: in Python 3.11 a ``join`` that Ctrl-C interrupts marks the thread stopped).
_RUNNING: set = set()
_LOCK = threading.Lock()

#: How often the main thread wakes while it waits, s.
POLL_S = 0.1


def map_in_threads(fn, items, workers: int = 2) -> list:
    """``[fn(x) for x in items]`` computed in up to ``workers`` daemon threads.

    The caller waits, waking every :data:`POLL_S`, so a KeyboardInterrupt (in the main
    thread) is raised at once; the first exception of ``fn`` is raised once all threads end.
    """
    items = list(items)
    results, errors, queue = [None] * len(items), [], iter(enumerate(items))
    take = threading.Lock()

    def run(done: threading.Event):
        try:
            while not errors:
                with take:
                    nxt = next(queue, None)
                if nxt is None:
                    return
                results[nxt[0]] = fn(nxt[1])
        except BaseException as exc:  # raised in the caller
            errors.append(exc)
        finally:
            done.set()
            with _LOCK:
                _RUNNING.discard(done)

    events = [threading.Event() for _ in range(max(1, min(workers, len(items))))]
    with _LOCK:
        _RUNNING.update(events)
    for k, done in enumerate(events):
        threading.Thread(target=run, args=(done,), daemon=True, name=f"lunarcap-{k}").start()
    for done in events:
        while not done.wait(POLL_S):
            pass
    if errors:
        raise errors[0]
    return results


def off_main_thread(fn, *args, **kwargs):
    """``fn(*args, **kwargs)``; from the main thread, run in a daemon thread (see module)."""
    if threading.current_thread() is not threading.main_thread():
        return fn(*args, **kwargs)
    return map_in_threads(lambda _: fn(*args, **kwargs), [None], 1)[0]


def busy() -> bool:
    """True while a thread of :func:`map_in_threads` still runs (e.g. after Ctrl-C)."""
    with _LOCK:
        return any(not done.is_set() for done in _RUNNING)
