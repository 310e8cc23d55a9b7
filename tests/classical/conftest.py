"""Fixtures of the classical tests."""
import pytest


@pytest.fixture
def checks(monkeypatch):
    """The step control's checks (``RichardsonCheck`` instances) of the calls the test makes, in order."""
    from hyperrotor.classical.solvers import richardson_check

    seen = []
    init = richardson_check.RichardsonCheck.__init__

    def spy(self, *args, **kwargs):
        init(self, *args, **kwargs)
        seen.append(self)

    monkeypatch.setattr(richardson_check.RichardsonCheck, "__init__", spy)
    return seen
