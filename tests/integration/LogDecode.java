// Decodes every event of an LCM log with lcm.jar and nerv's generated Java
// types, looking types up by fingerprint as lcm-spy does. Prints one line per
// channel and exits 1 when any event fails to decode or has an unknown type.
import java.io.DataInputStream;
import java.io.ByteArrayInputStream;
import java.util.HashMap;
import java.util.Map;
import java.util.TreeMap;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;
import java.util.Enumeration;

public class LogDecode {
  public static void main(String[] args) throws Exception {
    Map<Long, Class<?>> types = new HashMap<>();
    try (JarFile jar = new JarFile(args[1])) {
      for (Enumeration<JarEntry> e = jar.entries(); e.hasMoreElements();) {
        String name = e.nextElement().getName();
        if (!name.endsWith(".class") || name.contains("$")) continue;
        Class<?> c = Class.forName(name.replace('/', '.').replace(".class", ""));
        types.put(c.getField("LCM_FINGERPRINT").getLong(null), c);
      }
    }
    lcm.logging.Log log = new lcm.logging.Log(args[0], "r");
    Map<String, Integer> decoded = new TreeMap<>();
    int failures = 0;
    while (true) {
      lcm.logging.Log.Event ev;
      try { ev = log.readNext(); } catch (java.io.EOFException eof) { break; }
      if (ev.channel.equals("LCM_SELF_TEST")) continue;  // LCM's own start-up probe, not a typed message
      long fingerprint = new DataInputStream(new ByteArrayInputStream(ev.data)).readLong();
      Class<?> type = types.get(fingerprint);
      if (type == null) { System.out.println("unknown type on " + ev.channel); failures++; continue; }
      try {
        type.getConstructor(byte[].class).newInstance((Object) ev.data);
        decoded.merge(ev.channel + " " + type.getSimpleName(), 1, Integer::sum);
      } catch (Exception ex) {
        System.out.println("cannot decode " + ev.channel + ": " + ex.getCause());
        failures++;
      }
    }
    for (Map.Entry<String, Integer> e : decoded.entrySet()) System.out.println(e.getKey() + " " + e.getValue());
    System.exit(failures == 0 && !decoded.isEmpty() ? 0 : 1);
  }
}
