# The six demo goals, one home for the benchmark scripts that source this file (run.sh,
# defaults.sh, demo_speed.sh, demo_stages.sh, ab_stages.sh). Each entry is
# "short name|mesh in meshes/|optimize options".
demo_goals=(
  "stand|bottle.obj|--goal stand"
  "filled|bottle.obj|--goal stand-filled --fill-density 0.8 --outer"
  "top|top.obj|--goal spin"
  "rolypoly|rolypoly.obj|--goal roly-poly"
  "buoy|buoy.obj|--goal float --fluid-density 0.806"
  "sphere|sphere.obj|--goal volume --target-volume 20000"
)

# demo_goal_args NAME MESHES: sets the array `args` to goal NAME's mesh (in MESHES) and options,
# or says the name is unknown and returns 2.
demo_goal_args() {
  local entry name mesh opts
  for entry in "${demo_goals[@]}"; do
    IFS='|' read -r name mesh opts <<<"$entry"
    if [[ $name == "$1" ]]; then
      read -r -a args <<<"$opts"
      args=("$2/$mesh" "${args[@]}")
      return 0
    fi
  done
  echo "unknown goal name '$1'" >&2
  return 2
}
