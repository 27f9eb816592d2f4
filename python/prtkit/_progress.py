"""The progress bar behind ``progress=True``: a tqdm bar when tqdm is installed, else none."""


class _Bar:
    """A tqdm bar in percent, fed with the fraction done; closed when the call ends."""

    def __init__(self, tqdm, label):
        self._bar = tqdm(total=100, desc=label, unit="%", leave=False,
                         bar_format="{desc}: {percentage:3.0f}%|{bar}| {elapsed}<{remaining}")

    def __call__(self, fraction):
        n = int(round(fraction * 100))
        if n > self._bar.n:
            self._bar.update(n - self._bar.n)

    def close(self):
        self._bar.close()


def bar(label):
    """A callable for the library's progress, or None when tqdm is not installed."""
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return _Bar(tqdm, label)
