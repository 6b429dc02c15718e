# What the mapping tables share (mapping_table.jq, patrol_table.jq; jq -L scripts): figures in cm
# and per cent, "—" for a figure a run does not have, and a run's drift as its arguments gave it.

def cm: if . == null then "—" else (. * 1000 | round / 10 | tostring) end;
def pct: if . == null then "—" else (. * 1000 | round / 10 | tostring) + " %" end;
def count: if . == null then "—" else tostring end;
def pair($a; $b): "\($a | cm) / \($b | cm)";
def drift: (.drift | tostring) + (if (.sim_args | length) > 0 then " " + (.sim_args | join(" ")) else "" end)
  + (if .odom_frame != "world" then " (odom \(.odom_frame))" else "" end);
