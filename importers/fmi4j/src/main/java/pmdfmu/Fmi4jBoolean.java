/* SPDX-License-Identifier: BSD-2-Clause */
package pmdfmu;

import java.io.File;
import java.util.Arrays;

import no.ntnu.ihb.fmi4j.importer.fmi2.CoSimulationSlave;
import no.ntnu.ihb.fmi4j.importer.fmi2.Fmu;

/**
 * FMI4j's Boolean writes, for tests/test_java_importer.py: in Initialization Mode it writes one
 * Boolean variable through FMI4j's writeBoolean with value arrays of the lengths given (every
 * element the value, every value reference the variable's) and prints after each write the status
 * and the value readBoolean reads back, one line each: "LENGTH VALUE STATUS READ".
 *
 * Usage: Fmi4jBoolean FMU VALUE_REFERENCE true|false LENGTH...
 */
public final class Fmi4jBoolean {
    public static void main(String[] args) throws Exception {
        long vr = Long.parseLong(args[1]);
        boolean value = Boolean.parseBoolean(args[2]);
        try (Fmu fmu = Fmu.from(new File(args[0]));
             CoSimulationSlave slave = fmu.asCoSimulationFmu().newInstance()) {
            slave.setupExperiment(0.0, 0.0, 0.0);
            slave.enterInitializationMode();
            for (int i = 3; i < args.length; i++) {
                int n = Integer.parseInt(args[i]);
                long[] vrs = new long[n];
                boolean[] values = new boolean[n];
                Arrays.fill(vrs, vr);
                Arrays.fill(values, value);
                String status = slave.writeBoolean(vrs, values).name();
                boolean[] read = new boolean[1];
                slave.readBoolean(new long[] {vr}, read);
                System.out.println(n + " " + value + " " + status + " " + read[0]);
            }
            slave.terminate();
        }
    }
}
