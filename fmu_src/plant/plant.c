/* SPDX-License-Identifier: BSD-2-Clause */
/* The plant's physics (plant.h has the equations). */
#include <math.h>

#include "plant.h"

#define FULL_SCALE 32768.0       /* 2^15 counts of the chip's motor command: 100/2^15 % a count (docs/servo.md) */
#define TWO_PI 6.283185307179586
#define TWO_POW_32 4294967296.0
/* A rest of a communication step shorter than this many internal steps is a
 * master's rounding (3e-4 / 1e-5 is 29.999999999999996 in doubles), not time to integrate. */
#define REST_TOLERANCE 1e-9

/* The quadrature encoder, decoded 4x, wraps at 32 bits as the chip's position
 * registers do. */
int32_t plant_encoder_count(const PlantModel *m)
{
    double counts = fmod(floor(m->angle * (4.0 * m->encoderLines) / TWO_PI), TWO_POW_32);
    if (!isfinite(counts))                      /* an angle out of doubles' range: doStep refuses it */
        return 0;
    if (counts >= TWO_POW_32 / 2)
        counts -= TWO_POW_32;
    else if (counts < -TWO_POW_32 / 2)
        counts += TWO_POW_32;
    return (int32_t)counts;
}

/* The amplifier: a voltage source proportional to the command, the sum of the
 * two inputs (a model wires one of them), saturating at full scale. Full scale
 * is the chip's (its axisN.motorOutput is axisN.motorCommand / 2^15), and a
 * power of two, so the Integer wire and the Real one give the same voltage
 * bit for bit. */
static double amplifier_voltage(const PlantModel *m)
{
    double command = (double)m->motorCommand / FULL_SCALE + m->motorOutput;
    if (command > 1.0)
        command = 1.0;
    else if (command < -1.0)
        command = -1.0;
    return m->supplyVoltage * command;
}

void plant_start(PlantModel *m)
{
    m->angle = m->initialAngle;
    m->speed = m->initialSpeed;
    m->current = 0.0;
    m->voltage = 0.0;
    m->encoderCount = plant_encoder_count(m);
}

/* One step of h, semi-implicit Euler: the speed by backward Euler, friction
 * included as the set-valued law it is, then the angle with the new speed.
 * Backward Euler of J dw/dt = T0 - c w - Tc s, s in sgn(w), over h:
 *   (J + h c) w' = J w + h T0 - h Tc s =: p - h Tc s
 * has exactly one solution: w' = 0 when |p| <= h Tc (friction can take up the
 * whole impulse: the shaft stops or sticks in this step), else
 * w' = (p - h Tc sgn p) / (J + h c). It is stable for any h, its steady speed
 * is the exact (T0 - Tc) / c, and a stopping shaft stops instead of chattering
 * around 0. */
static void step(PlantModel *m, double h, double voltage)
{
    const double R = m->armatureResistance, k = m->torqueConstant;
    const double J = m->rotorInertia + m->loadInertia;
    const double c = k * k / R + m->viscousFriction;
    const double p = J * m->speed + h * (k * voltage / R + m->loadTorque);
    const double stiction = h * m->coulombFriction;
    if (fabs(p) <= stiction)
        m->speed = 0.0;
    else
        m->speed = (p - copysign(stiction, p)) / (J + h * c);
    m->angle += h * m->speed;
    m->current = (voltage - k * m->speed) / R;
}

double plant_internal_steps(const PlantModel *m, double h)
{
    return ceil(h / m->internalStep);
}

void plant_advance(PlantModel *m, double h)
{
    const double voltage = amplifier_voltage(m);
    const double whole = floor(h / m->internalStep + REST_TOLERANCE);
    const double rest = h - whole * m->internalStep;
    double n;
    for (n = 0; n < whole; n++)
        step(m, m->internalStep, voltage);
    if (rest > REST_TOLERANCE * m->internalStep)
        step(m, rest, voltage);
    m->voltage = voltage;
    m->encoderCount = plant_encoder_count(m);
}
