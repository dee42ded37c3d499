"""The FMU state as bytes, for tests that compare states (a refused call changes nothing)."""


def snapshot(chip) -> bytes:
    """The serialized FMU state of a pmdfmu.Chip (or anything with an FMPy slave as .fmu)."""
    state = chip.fmu.getFMUState()
    try:
        return bytes(chip.fmu.serializeFMUState(state))
    finally:
        chip.fmu.freeFMUState(state)
