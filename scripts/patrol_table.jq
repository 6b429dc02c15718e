# The runs of eval_mapping --patrol among the results given as inputs (the others are skipped):
# exploration, then each robot on a looped mission through random places until the run ends. One row
# per run: the whole run's pose error, then the patrol's alone (corrected and raw odometry) and how
# close to its places the robots truly were when the planner counted them reached.

include "mapping_defs";

[inputs | select(.after_exploration == "patrol")] | sort_by(.world, .protocol, .drift, (.sim_args | join(" ")), .seed)
| (["| world | protocol | drift | seed | explored (sim s) | whole run: ATE corrected RMSE / max (cm) | patrol: ATE corrected RMSE / max (cm) | patrol: ATE raw RMSE / max (cm) | patrol: goal mean / max (cm, n) | occupied near a wall | walls found | closures | false closures | run |",
    "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
   + map("| \(.world) | \(.protocol) | \(drift) | \(.seed) "
       + "| \(if .patrol == null then "not done" else (.patrol.started_s | round | tostring) end) "
       + "| \(pair(.ate_corrected.rmse_m; .ate_corrected.max_m)) "
       + "| \(pair(.patrol.ate_corrected.rmse_m; .patrol.ate_corrected.max_m)) "
       + "| \(pair(.patrol.ate_raw.rmse_m; .patrol.ate_raw.max_m)) "
       + "| \(pair(.patrol.goal_true.mean_m; .patrol.goal_true.max_m)) (\(.patrol.goal_true.count | count)) "
       + "| \(.map.near_wall_share | pct) | \(.map.wall_found_share | pct) "
       + "| \(.slam_counters.slam_closures_accepted | count) | \(.closures.false_closures | count) "
       + "| \(.simulated_s / 60 | round) sim min at ×\(.achieved_speed * 10 | round / 10), [image](images/mapping/\(.image)) |"))[]
