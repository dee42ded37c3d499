/* Seed 000, section 1.2 "The format of the trajectory data", compiled as printed: its typedefs
   and the VelocityProfile structure, token for token. The PDF extraction set them as table
   cells ("| typedef long PMDFIXED32; |", a declaration split over cells); the cell borders are
   dropped and each declaration put back on its line with its comment.
   Around it: one VelocityProfile per segment of the scenario's table for axis 1, uploaded with
   WriteBuffer into five buffers of their own (the section shows no upload), then run as an
   external profile; tests/test_cmotion.py compares every cycle with the reference model. */
#include "seed_support.h"

/* ---- seed 000, 1.2 ---- */
typedef long PMDFIXED32;            // -2,147,483,648 to 2,147,483,647
typedef long PMDFIXED1616;          // -16384 to 16383 + 65535/65536
typedef long PMDFIXED032;           // -2,147,483,648 to 2,147,483,647/4,294,967,296
typedef unsigned long PMD_UINT32;   // 0 to 4,294,967,296
typedef unsigned short PMD_UINT16;  // 0 to 32,768
typedef PMDFIXED32 PMD_POSITION;    // count
typedef PMDFIXED1616 PMD_VELOCITY;  // count/cycle
typedef PMDFIXED1616 PMD_ACCELERATION;  // count/(cycle*cycle)
typedef PMDFIXED032 PMD_JERK;       // count/(cycle*cycle*cycle)
typedef PMD_UINT32 PMD_TIME;        // cycle

typedef struct PMD_VelocityProfile  // velocity profile per axis
{
    PMD_POSITION position;          // position
    PMD_VELOCITY velocity;          // velocity
    PMD_ACCELERATION acceleration;  // acceleration
    PMD_JERK jerk;                  // jerk
    PMD_TIME time;                  // time
} VelocityProfile;
/* ---- end of 1.2 ---- */

enum { buffer_base = 0x200, buffer_size = 16 };

int main(void)
{
    VelocityProfile segments[SEED_ENTRIES];
    int i, variable;
    seed_open();
    for (i = 0; i < SEED_ENTRIES; i++) {
        segments[i].position = seed_entry(0, 0, i);
        segments[i].velocity = seed_entry(0, 1, i);
        segments[i].acceleration = seed_entry(0, 2, i);
        segments[i].jerk = seed_entry(0, 3, i);
        segments[i].time = (PMD_TIME)seed_entry(0, 4, i);
    }
    for (variable = 0; variable < seed_variables; variable++) {
        PMDuint16 id = (PMDuint16)(2 + variable);
        check(PMDSetBufferStart(&hAxis[PMDAxis1], id, buffer_base + (PMDuint32)variable * buffer_size),
              "PMDSetBufferStart");
        check(PMDSetBufferLength(&hAxis[PMDAxis1], id, buffer_size), "PMDSetBufferLength");
        check(PMDSetBufferFunction(&hAxis[PMDAxis1], (PMDint16)variable, (PMDint16)id), "PMDSetBufferFunction");
    }
    for (i = 0; i < SEED_ENTRIES; i++) {     /* a structure's fields go to their variables' buffers */
        check(PMDWriteBuffer(&hAxis[PMDAxis1], 2, (PMDint32)segments[i].position), "PMDWriteBuffer");
        check(PMDWriteBuffer(&hAxis[PMDAxis1], 3, (PMDint32)segments[i].velocity), "PMDWriteBuffer");
        check(PMDWriteBuffer(&hAxis[PMDAxis1], 4, (PMDint32)segments[i].acceleration), "PMDWriteBuffer");
        check(PMDWriteBuffer(&hAxis[PMDAxis1], 5, (PMDint32)segments[i].jerk), "PMDWriteBuffer");
        check(PMDWriteBuffer(&hAxis[PMDAxis1], 6, (PMDint32)segments[i].time), "PMDWriteBuffer");
    }
    check(PMDSetProfileMode(&hAxis[PMDAxis1], PMDExternalProfile), "PMDSetProfileMode");
    check(PMDUpdate(&hAxis[PMDAxis1]), "PMDUpdate");
    run_cycles(SEED_ENTRIES * SEGMENT_CYCLES);
    seed_close();
    return 0;
}
