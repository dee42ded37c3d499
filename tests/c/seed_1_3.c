/* Seed 000, section 1.3 "Populating the trajectory data buffers": its three snippets compiled as
   printed, chosen by the first argument:
     writebuffer   the WriteBuffer upload
     dpram         the dual-port upload (PMDPCI_WriteDPRAM, a call of the library: PMDfmu.h)
     refill        the WriteBuffer upload, then, 100 cycles into the profile, the refill by the
                   buffer indexes
   Around them (seed_support.h, as plain library calls): 1.1's buffers for three axes, 1.4's
   initial moves and synchronized start, and the cycles run. Added declarations: the sizes the
   snippets name (num_axes, num_variables, num_data_entries; memory_start, memory_size as 1.1
   sets them), buffer_id, write_offset, buffer_length, free_buffer_entries. Its storage
   type PMDUINT32 is the library's (host/c/PMDfmu_types.h).

   The snippets declare `data` and then read it: "the storage structure is simplified", so the
   program fills it (fill(), the scenario's tables) between the declaration and the loop.

   Three changes, each beside the seed's text below:
   - the dual-port call passes `&hAxis[axis]->transport_data`: hAxis is an array of handle
     structures (the other snippets pass &hAxis[axis]), so hAxis[axis] has no `->`; the smallest
     change that compiles is `.`, the address of the handle's transport_data, as meant.
   - the refill's three minus signs are printed as en dashes (U+2013, the PDF's typesetting),
     which are no C token; they are '-' here.
   The dual-port call's last argument, data[axis][variable][0], is the block's first word itself,
   not its address: PMDPCI_WriteDPRAM is the library's macro that takes that word and passes its
   address (PMDfmu.h), so that line compiles as printed. Its offset is a word address of the
   external memory, from 0: as printed (without memory_start) the seed writes below the buffers,
   and the chip runs what the buffers then hold, as the Python transcription does. */
#include "seed_support.h"

enum { num_axes = 3, num_variables = seed_variables, num_data_entries = SEED_ENTRIES };
static const int memory_start = seed_memory_start, memory_size = seed_memory_size;
static int buffer_id, write_offset, buffer_length;

static void fill(PMDUINT32 data[num_axes][num_variables][num_data_entries])
{
    int axis, variable, index;
    for (axis = 0; axis < num_axes; axis++)
        for (variable = 0; variable < num_variables; variable++)
            for (index = 0; index < num_data_entries; index++)
                data[axis][variable][index] = (PMDUINT32)seed_entry(axis, variable, index);
}

static void upload_writebuffer(void)
{
/* ---- seed 000, 1.3, first snippet ---- */
// the storage structure is simplified to an array of 32-bit values
PMDUINT32 data[num_axes][num_variables][num_data_entries];
    fill(data);     /* added: the values the host uploads */
for (int axis = 0; axis < num_axes; axis++)
for (int variable = 0; variable < num_variables; variable++)
for (int index = 0; index < num_data_entries; index++)
{
// the buffer_id starts at 2
buffer_id = 2+(axis*num_variables)+variable;
PMDWriteBuffer(&hAxis[axis],buffer_id,
data[axis][variable][index]);
}
/* ---- end ---- */
}

static void upload_dpram(void)
{
    PMDUINT32 data[num_axes][num_variables][num_data_entries];    /* the first snippet's storage */
    fill(data);
/* ---- seed 000, 1.3, second snippet ---- */
for (int axis = 0; axis < num_axes; axis++)
for (int variable = 0; variable < num_variables; variable++)
{
// the buffer_id starts at 2
write_offset = axis*variable*buffer_length;
/* seed: PMDPCI_WriteDPRAM(&hAxis[axis]->transport_data, */
PMDPCI_WriteDPRAM(&hAxis[axis].transport_data,
write_offset,num_data_entries,
data[axis][variable][0]);
}
/* ---- end ---- */
}

/* the refill writes up to memory_size - memory_start entries per variable from `data` */
static PMDUINT32 data[num_axes][num_variables][seed_memory_size - seed_memory_start];

static void refill(void)
{
    PMDUINT32 free_buffer_entries;
    int axis, variable;
    unsigned index;
    for (axis = 0; axis < num_axes; axis++)
        for (variable = 0; variable < num_variables; variable++)
            for (index = 0; index < sizeof data[0][0] / sizeof data[0][0][0]; index++)
                data[axis][variable][index] = (PMDUINT32)seed_entry(axis, variable, (int)(index % SEED_ENTRIES));
    {
/* ---- seed 000, 1.3, third snippet ---- */
PMDUINT32 readindex, writeindex;
// read the indexes for the position buffer (buffer #2) of axis#
// the read/write index will be the same for all variables
// since they are read as a set
PMDGetBufferReadIndex(&hAxis[PMDAxis1],2,&readindex);
PMDGetBufferWriteIndex(&hAxis[PMDAxis1],2,&writeindex);
if (readindex > writeindex)
free_buffer_entries = readindex - writeindex;       /* seed: readindex – writeindex */
else
free_buffer_entries =
(memory_size - memory_start) - (writeindex          /* seed: (memory_size – memory_start) – (writeindex */
- readindex);                                       /* seed: – readindex); */
for (int variable = 0; variable < num_variables; variable++)
for (int index = 0; index < free_buffer_entries;
index++)
{
// the buffer_id starts at 2
buffer_id = 2+variable;
PMDWriteBuffer(&hAxis[PMDAxis1],buffer_id,
data[PMDAxis1][variable][index]);
}
/* ---- end ---- */
        printf("R refill %lu %lu %lu\n", (unsigned long)readindex, (unsigned long)writeindex,
               (unsigned long)free_buffer_entries);
    }
}

int main(int argc, char **argv)
{
    const char *mode = argc > 1 ? argv[1] : "writebuffer";
    PMDuint32 readindex = 0, writeindex = 0;
    seed_open();
    buffer_length = (int)setup_buffers(num_axes);
    if (strcmp(mode, "dpram") == 0)
        upload_dpram();
    else
        upload_writebuffer();
    check(PMDGetBufferReadIndex(&hAxis[PMDAxis1], 2, &readindex), "PMDGetBufferReadIndex");
    check(PMDGetBufferWriteIndex(&hAxis[PMDAxis1], 2, &writeindex), "PMDGetBufferWriteIndex");
    printf("R indexes %lu %lu\n", (unsigned long)readindex, (unsigned long)writeindex);
    initial_moves(num_axes);
    wait_at_rest(num_axes);
    start_external(num_axes);
    if (strcmp(mode, "refill") == 0) {
        run_cycles(100);
        refill();
    }
    run_cycles(1500);
    seed_close();
    return 0;
}
