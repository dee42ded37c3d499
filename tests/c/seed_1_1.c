/* Seed 000, section 1.1 "Setting up the trajectory data buffers", compiled as printed.
   Added around it: the variables it assigns without declaring (num_axes, final_variable,
   memory_start, memory_size, buffer_id, buffer_start, buffer_length) and num_variables, which it
   uses (the five trajectory variables). The text is the seed's token for token; only the layout
   its PDF extraction broke is restored: its comment on buffer_id came out as "//" lines apart from
   their words, which would leave the words outside the comment.
   The snippet declares C-Motion's buffer-function enum itself, so the header's copy steps aside
   (PMD_OMIT_CONSTANTS_BufferFunction): C allows an enumeration constant only once. */
#define PMD_OMIT_CONSTANTS_BufferFunction
#include "seed_support.h"

static int num_axes, final_variable, memory_start, memory_size, buffer_id, buffer_start, buffer_length;
static const int num_variables = 5;

/* ---- seed 000, 1.1 ---- */
enum { PMDBufferFunctionNone=-1, PMDBufferFunctionPosition=0,
PMDBufferFunctionVelocity, PMDBufferFunctionAcceleration,
PMDBufferFunctionJerk, PMDBufferFunctionTime };

static void seed_1_1(void)
{
num_axes = 2;
final_variable = PMDBufferFunctionTime;
memory_start = 0x200; // first 1Kx16 reserved by motion processor
memory_size = 0x4000; // 16Kx32
buffer_id = 2; // ID 0 is reserved for the trace buffer
               // ID 1 is also used as a read index for
               // the trace buffer
buffer_start = memory_start;
buffer_length = (memory_size - memory_start)/(num_axes*num_variables);
for (int axis = 0; axis < num_axes; axis++)
for (int variable = 0; variable <= final_variable;
variable++)
{
buffer_start = memory_start+(axis*variable*buffer_length);
PMDSetBufferStart(&hAxis[axis],buffer_id,buffer_start);
PMDSetBufferLength(&hAxis[axis],buffer_id,buffer_length);
// assign a trajectory variable to the buffer
PMDSetBufferFunction(&hAxis[axis],variable,buffer_id);
buffer_id++;
}
}
/* ---- end of 1.1 ---- */

int main(void)
{
    int id, axis, function;
    seed_open();
    seed_1_1();
    printf("R buffer_length %d\n", buffer_length);
    for (id = 2; id < buffer_id; id++) {
        PMDuint32 start = 0, length = 0;
        check(PMDGetBufferStart(&hAxis[PMDAxis1], (PMDuint16)id, &start), "PMDGetBufferStart");
        check(PMDGetBufferLength(&hAxis[PMDAxis1], (PMDuint16)id, &length), "PMDGetBufferLength");
        printf("R buffer %d %lu %lu\n", id, (unsigned long)start, (unsigned long)length);
    }
    for (axis = 0; axis < num_axes; axis++)
        for (function = PMDBufferFunctionPosition; function <= PMDBufferFunctionTime; function++) {
            PMDint16 id16 = 0;
            check(PMDGetBufferFunction(&hAxis[axis], (PMDint16)function, &id16), "PMDGetBufferFunction");
            printf("R function %d %d %d\n", axis, function, id16);
        }
    seed_close();
    return 0;
}
