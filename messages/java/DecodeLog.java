// Headless check of what lcm-spy shows: reads an lcm-logger file and decodes every event
// whose type fingerprint is one of the h4msgs Java types on the class path, looked up the
// way lcm-spy looks them up (lcm.spy.LCMTypeDatabase). Prints one line per channel (count,
// type, the last pose_id) and exits 1 when an H4_ channel carries a message no type decodes.
//   java -cp lcm.jar:h4msgs.jar:DIR DecodeLog campaign.lcmlog
import java.io.DataInputStream;
import java.io.ByteArrayInputStream;
import java.io.DataInput;
import java.io.EOFException;
import java.util.Map;
import java.util.TreeMap;

import lcm.logging.Log;
import lcm.spy.LCMTypeDatabase;

public class DecodeLog {
  static final class ChannelCount {
    String type = "?";
    long decoded = 0;
    long failed = 0;
    String lastPoseId = "";
  }

  public static void main(String[] args) throws Exception {
    if (args.length != 1) {
      System.err.println("usage: DecodeLog LOGFILE");
      System.exit(2);
    }
    LCMTypeDatabase types = new LCMTypeDatabase();
    Log log = new Log(args[0], "r");
    Map<String, ChannelCount> channels = new TreeMap<>();
    while (true) {
      Log.Event event;
      try {
        event = log.readNext();
      } catch (EOFException end) {
        break;
      }
      ChannelCount count = channels.computeIfAbsent(event.channel, c -> new ChannelCount());
      try {
        DataInputStream in = new DataInputStream(new ByteArrayInputStream(event.data));
        long fingerprint = new DataInputStream(new ByteArrayInputStream(event.data)).readLong();
        Class<?> cls = types.getClassByFingerprint(fingerprint);
        if (cls == null) throw new IllegalStateException("unknown fingerprint");
        Object message = cls.getConstructor(DataInput.class).newInstance(in);
        count.type = cls.getName();
        try {
          count.lastPoseId = String.valueOf(cls.getField("pose_id").get(message));
        } catch (NoSuchFieldException none) {
          count.lastPoseId = "-";
        }
        ++count.decoded;
      } catch (Exception e) {
        ++count.failed;
      }
    }
    boolean ok = true;
    for (Map.Entry<String, ChannelCount> e : channels.entrySet()) {
      ChannelCount c = e.getValue();
      System.out.printf("%-20s %-26s decoded %6d  failed %d  last pose_id %s%n", e.getKey(),
                        c.type, c.decoded, c.failed, c.lastPoseId);
      if (e.getKey().startsWith("H4_") && c.failed > 0) ok = false;
    }
    System.exit(ok && !channels.isEmpty() ? 0 : 1);
  }
}
