# Sourced by scripts/sponza_bias.sh and scripts/vpl_sampling_sun.sh: one small IGI or
# path-traced render of a scene, kept when its image already exists. Needs BIN (where
# igi-master is), W and H.
render() {  # scene out frames extra...
    local scene=$1 out=$2 frames=$3; shift 3
    [ -s "$out" ] && return 0
    nice -n 19 "$BIN/igi-master" --scene "$scene" --allow-outside-paths --local-clients 1 \
        --width "$W" --height "$H" --frames "$frames" --output "$out" --log-level warn \
        --listen 127.0.0.1:0 "$@" > "${out%.exr}.log" 2>&1
}
