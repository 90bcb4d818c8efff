// Decodes every event of an LCM log the way lcm-spy does (lcm.spy.LCMTypeDatabase
// over the CLASSPATH, then the type's DataInput constructor), so a test can prove
// without a display that lcm-spy shows no undecodable message.
// Usage: java -cp lcm.jar:lcm_control_types.jar:decode_log.jar DecodeLog LOGFILE
// Prints one line per channel (channel, type, count) and exits 1 if any event
// could not be decoded or the log is empty.
import java.io.DataInputStream;
import java.io.ByteArrayInputStream;
import java.io.DataInput;
import java.io.EOFException;
import java.util.TreeMap;

public class DecodeLog {
    public static void main(String[] args) throws Exception {
        if (args.length != 1) {
            System.err.println("usage: DecodeLog LOGFILE");
            System.exit(2);
        }
        lcm.spy.LCMTypeDatabase db = new lcm.spy.LCMTypeDatabase();
        lcm.logging.Log log = new lcm.logging.Log(args[0], "r");
        TreeMap<String, String> types = new TreeMap<>();
        TreeMap<String, Integer> counts = new TreeMap<>();
        int total = 0, bad = 0;
        while (true) {
            lcm.logging.Log.Event ev;
            try {
                ev = log.readNext();
            } catch (EOFException e) {
                break;
            }
            total++;
            counts.merge(ev.channel, 1, Integer::sum);
            String type = "UNDECODABLE";
            try {
                long fp = new DataInputStream(new ByteArrayInputStream(ev.data)).readLong();
                Class<?> cls = db.getClassByFingerprint(fp);
                if (cls != null) {
                    cls.getConstructor(DataInput.class)
                        .newInstance(new DataInputStream(new ByteArrayInputStream(ev.data)));
                    type = cls.getName();
                }
            } catch (Exception e) {
                type = "UNDECODABLE (" + e + ")";
            }
            if (type.startsWith("UNDECODABLE")) bad++;
            String prev = types.get(ev.channel);
            if (prev == null || type.startsWith("UNDECODABLE")) types.put(ev.channel, type);
        }
        for (String ch : counts.keySet())
            System.out.println(ch + " " + types.get(ch) + " " + counts.get(ch));
        System.out.println("events " + total + ", undecodable " + bad);
        System.exit(total > 0 && bad == 0 ? 0 : 1);
    }
}
