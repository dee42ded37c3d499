import pytest

import pmdfmu


@pytest.fixture
def chip():
    with pmdfmu.Chip() as c:
        yield c
