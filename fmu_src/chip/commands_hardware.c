/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's hardware interfaces (reference 1.2, "Miscellaneous" and the
 * commutation commands) that no row of registers.csv can serve (a packed or
 * paired word, an address or channel, a reply of their own): the AxisOut pin,
 * the serial port, the encoder-to-step ratio, the peripheral I/O bus, the
 * analog inputs, the firmware checksum and the phasing of the commutator. The
 * FMU has no serial port, AxisOut pin, step output or commutator: those
 * commands store what the host sets and read it back, and otherwise the chip
 * acts as one whose hardware is idle. The I/O bus and the analog inputs are
 * FMU variables a plant model drives. modelDescription/hardware.csv says what
 * each command does here (docs/commands.md shows it). */
#include "commands.h"

/* GetChecksum: the MC2440 application's self-test expects 0x12345678, "as the
 * programming manual defines it" (reference S3, PMDsetup.c); the FMU has no
 * firmware image to sum, so it answers that value. */
#define PMD_NAVIGATOR_CHECKSUM 0x12345678u

/* ---- the AxisOut pin ---- */

int cmd_SetAxisOutSource(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    uint32_t word = 0;
    (void)reply;
    if (arg[0] >= PMD_AXES || arg[2] > PMDAxisOutSourceSignalStatus) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: SetAxisOutSource(%lld, %lld, %lld): the source axis is 0..%d and the "
                "register 0 (none), 1 (event), 2 (activity) or 3 (signal status)", axis + 1, (long long)arg[0],
                (long long)arg[1], (long long)arg[2], PMD_AXES - 1);
        return PMD_ERR_InvalidParameter;
    }
    word = PMD_FIELD_DP(word, PMDAxisOutSourceAxis, arg[0]);
    word = PMD_FIELD_DP(word, PMDAxisOutSourceBit, arg[1]);
    word = PMD_FIELD_DP(word, PMDAxisOutSourceRegister, arg[2]);
    AXIS(axis)->axisOutSource = (uint16_t)word;
    return 0;
}

int cmd_GetAxisOutSource(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    uint16_t word = AXIS(axis)->axisOutSource;
    (void)arg;
    reply[0] = PMD_FIELD_EX(word, PMDAxisOutSourceAxis);
    reply[1] = PMD_FIELD_EX(word, PMDAxisOutSourceBit);
    reply[2] = PMD_FIELD_EX(word, PMDAxisOutSourceRegister);
    return 0;
}

/* ---- the serial port (reference 3.3) ---- */

int cmd_SetSerialPortMode(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    uint32_t word = 0;
    (void)axis; (void)reply;
    /* the Navigator's codes: baud 0..7, parity 0..2, protocol 0, 2 or 3 (1 is the Magellan's idle line) */
    if (arg[0] > PMDSerialBaud416667 || arg[1] > PMDSerialParityEven || arg[3] == 1) {
        pmd_log(chip, PMD_LOG_ERRORS, "SetSerialPortMode(%lld, %lld, %lld, %lld, %lld): baud is 0..7, parity 0..2 and "
                "protocol 0, 2 or 3", (long long)arg[0], (long long)arg[1], (long long)arg[2], (long long)arg[3],
                (long long)arg[4]);
        return PMD_ERR_InvalidParameter;
    }
    word = PMD_FIELD_DP(word, PMDSerialPortBaud, arg[0]);
    word = PMD_FIELD_DP(word, PMDSerialPortParity, arg[1]);
    word = PMD_FIELD_DP(word, PMDSerialPortStopBits, arg[2]);
    word = PMD_FIELD_DP(word, PMDSerialPortProtocol, arg[3]);
    word = PMD_FIELD_DP(word, PMDSerialPortMultiDropID, arg[4]);
    chip->s.serialPortMode = (uint16_t)word;
    return 0;
}

int cmd_GetSerialPortMode(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    uint16_t word = chip->s.serialPortMode;
    (void)axis; (void)arg;
    reply[0] = PMD_FIELD_EX(word, PMDSerialPortBaud);
    reply[1] = PMD_FIELD_EX(word, PMDSerialPortParity);
    reply[2] = PMD_FIELD_EX(word, PMDSerialPortStopBits);
    reply[3] = PMD_FIELD_EX(word, PMDSerialPortProtocol);
    reply[4] = PMD_FIELD_EX(word, PMDSerialPortMultiDropID);
    return 0;
}

/* ---- the encoder-to-step ratio: two words (reference 1.2) ---- */

int cmd_SetEncoderToStepRatio(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    AXIS(axis)->encoderCounts = (uint16_t)arg[0];
    AXIS(axis)->encoderSteps = (uint16_t)arg[1];
    return 0;
}

int cmd_GetEncoderToStepRatio(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = AXIS(axis)->encoderCounts;
    reply[1] = AXIS(axis)->encoderSteps;
    return 0;
}

/* ---- the peripheral I/O bus and the analog inputs: FMU variables ---- */

static int io_address(PmdChip *chip, const char *command, int64_t address)
{
    if (address < PMD_IO_PORTS)
        return 0;
    pmd_log(chip, PMD_LOG_ERRORS, "%s(address %lld): the FMU's I/O bus decodes addresses 0..%d (io.input and "
            "io.output[1..%d])", command, (long long)address, PMD_IO_PORTS - 1, PMD_IO_PORTS);
    return PMD_ERR_InvalidParameter;
}

int cmd_WriteIO(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = io_address(chip, "WriteIO", arg[0]);
    (void)axis; (void)reply;
    if (!err)
        chip->s.ioOutput[arg[0]] = (uint16_t)arg[1];
    return err;
}

int cmd_ReadIO(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = io_address(chip, "ReadIO", arg[0]);
    (void)axis;
    if (!err)
        reply[0] = chip->s.ioInput[arg[0]];
    return err;
}

int cmd_ReadAnalog(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis;
    if (arg[0] >= PMD_ANALOG_CHANNELS) {
        pmd_log(chip, PMD_LOG_ERRORS, "ReadAnalog(channel %lld): the channels are 0..%d (the inputs analog[1..%d])",
                (long long)arg[0], PMD_ANALOG_CHANNELS - 1, PMD_ANALOG_CHANNELS);
        return PMD_ERR_InvalidParameter;
    }
    reply[0] = chip->s.analogInput[arg[0]];
    return 0;
}

int cmd_GetChecksum(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg;
    reply[0] = PMD_NAVIGATOR_CHECKSUM;
    return 0;
}

/* ---- commutation and phasing: an idle commutator ---- */

/* Phasing needs no motor motion here (there is no commutator to align), so
 * it completes at once: activity status bit 0 (PMDActivityPhasingInitialized)
 * is set from this command on, until a Reset. */
int cmd_InitializePhase(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg; (void)reply;
    AXIS(axis)->phasingInitialized = 1;
    return 0;
}

/* The FMU's motor is brushed (GetVersion: motor type PMDBrushedServo): its one
 * output, the motor command, drives phase A; phases B and C carry nothing. */
int cmd_GetPhaseCommand(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    if (arg[0] > PMDPhaseC) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: GetPhaseCommand(%lld): the phase is 0 (A), 1 (B) or 2 (C)", axis + 1,
                (long long)arg[0]);
        return PMD_ERR_InvalidParameter;
    }
    reply[0] = pmd_phase_command(AXIS(axis), (int)arg[0]);
    return 0;
}
