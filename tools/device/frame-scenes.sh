# The scenes the device scripts time frames of, by name; sourced by multi-device-run.sh,
# multi-gpu-scaling.sh and gpu-session.sh (run from the repository root, build/bare built).
# `frame_scene NAME` sets scene_args to the scene's file and the flags it needs.
frame_scene() {
  case $1 in
    cornell) scene_args=(scenes/cornell-box/CornellBox-Original.obj) ;;
    # An OBJ without its .mtl: nothing but a white sky lights it.
    dragon) scene_args=(.deps/shared/scenes/stanford-dragon-100k/dragon.obj --env 1,1,1) ;;
    # The bench's generated 5.2M-triangle scene, written once per node.
    large) [ -f /tmp/large/large.obj ] || { mkdir -p /tmp/large && build/bare/geocold-large-mesh /tmp/large/large.obj; }
           scene_args=(/tmp/large/large.obj) ;;
    *) echo "unknown scene '$1' (cornell, dragon, large)" >&2; return 1 ;;
  esac
}
