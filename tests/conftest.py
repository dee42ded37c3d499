import pytest

import pmdfmu


@pytest.fixture
def chip():
    with pmdfmu.Chip() as c:
        yield c


@pytest.fixture(params=[2, 3], ids=["fmi2", "fmi3"])
def any_chip(request):
    """A chip through each FMI version: the behaviour must not depend on it."""
    with pmdfmu.Chip(fmi_version=request.param) as c:
        yield c
