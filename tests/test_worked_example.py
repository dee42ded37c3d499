"""Seed 000's worked table, chip times 11003..11013, out of the FMU cycle by cycle."""
import pmdfmu
from pmdfmu import PMDBufferFunctionPosition, PMDBufferFunctionTime, PMDBufferFunctionVelocity

# chip time, commanded position, commanded velocity (the table's rows)
WORKED_TABLE = [(11003, 0, 0x10000), (11004, 1, 0x10000), (11005, 2, 0x10000), (11006, 3, 0x10000),
                (11007, 4, 0x10000), (11008, 5, 0x10000), (11009, 6, 0x10000), (11010, 7, 0x10000),
                (11011, 8, 0x10000), (11012, 9, 0x10000), (11013, 10, 0)]


def run_worked_example(chip):
    """The seed's two rows, started so that the first is read at chip time 11003."""
    ax = chip.axis(pmdfmu.PMDAxis1)
    for buffer_id, function, address in ((2, PMDBufferFunctionPosition, 0x200),
                                         (3, PMDBufferFunctionVelocity, 0x210),
                                         (4, PMDBufferFunctionTime, 0x220)):
        ax.SetBufferStart(buffer_id, address)
        ax.SetBufferLength(buffer_id, 2)
        ax.SetBufferFunction(function, buffer_id)
    # "Initial set of values": position 0, velocity 10000h, time 10; then 10, 0, 15
    for position, velocity, time in ((0, 0x10000, 10), (10, 0, 15)):
        ax.WriteBuffer(2, position)
        ax.WriteBuffer(3, velocity)
        ax.WriteBuffer(4, time)
    chip.run(11003)
    assert ax.GetTime() == 11002
    ax.SetProfileMode(pmdfmu.PMDExternalProfile)
    ax.Update()
    return chip.run(11, record=["axis1.commandedPosition", "axis1.commandedVelocity",
                                "axis1.commandedAcceleration", "axis1.activityStatus"])


def test_worked_table_comes_out_cycle_by_cycle(any_chip):
    rows = run_worked_example(any_chip)
    got = [(int(r["cycle"]), int(r["axis1.commandedPosition"]), int(r["axis1.commandedVelocity"])) for r in rows]
    assert got == WORKED_TABLE
    assert (rows["axis1.commandedAcceleration"] == 0).all()
    # ProfileSegment = 1 throughout: the second row (time 15) is still running at 11013
    assert all(r & pmdfmu.PMDActivityProfileSegmentMask == 0x2000 for r in rows["axis1.activityStatus"])


def test_velocity_1_0_is_10000h():
    assert pmdfmu.fixed_16_16(1.0) == 0x10000
