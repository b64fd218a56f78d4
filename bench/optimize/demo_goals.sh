# The six demo goals by short name (bench/optimize/run.sh's cases), for the scripts that source
# this file (demo_stages.sh, ab_stages.sh): `demo_goal_args NAME MESHES` sets the array `args` to
# the goal's mesh and options, or says the name is unknown and returns 2.
# Names: stand filled top rolypoly buoy sphere.
demo_goal_args() {
  local meshes=$2
  case $1 in
    stand) args=("$meshes/bottle.obj" --goal stand) ;;
    filled) args=("$meshes/bottle.obj" --goal stand-filled --fill-density 0.8 --outer) ;;
    top) args=("$meshes/top.obj" --goal spin) ;;
    rolypoly) args=("$meshes/rolypoly.obj" --goal roly-poly) ;;
    buoy) args=("$meshes/buoy.obj" --goal float --fluid-density 0.806) ;;
    sphere) args=("$meshes/sphere.obj" --goal volume --target-volume 20000) ;;
    *) echo "unknown goal name '$1'" >&2; return 2 ;;
  esac
}
