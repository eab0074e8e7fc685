# Sourced by run.sh and culling.sh: droplet_scene DIR N "W, H, D" "X, Y, Z" writes DIR/drops.csv
# (N droplets uniform in a 1 m cube above the ground, radii 12 mm · (1000/N)^½ · (0.5–1.5): the same
# screen coverage at every N) and DIR/s.json (ground, an opaque wall of that size at that place, a sun with hard
# shadows, environment light; camera 2.4 m away).
droplet_scene() {
    awk -v n="$2" 'BEGIN { srand(11); print "x,y,z,r"; r = 0.012 * sqrt(1000 / n)
        for (i = 0; i < n; i++) printf "%.5f,%.5f,%.5f,%.4e\n", rand() - 0.5, 0.5 + rand(), rand() - 0.5, r * (0.5 + rand()) }' \
        >"$1/drops.csv"
    cat >"$1/s.json" <<JSON
{"program": "csg", "camera": {"position": [0.2, 1.0, 2.4], "look_at": [0, 1.0, 0], "fov": 40},
 "environment": {"color": [0.6, 0.7, 0.9], "intensity": 1},
 "lights": [{"type": "directional", "direction": [0.4, 0.8, 0.45], "intensity": 2.5, "shadow": "hard"}],
 "materials": {"ground": {"base_color": [0.5, 0.45, 0.4], "roughness": 0.8},
               "wall": {"base_color": [0.7, 0.2, 0.15], "roughness": 0.5}},
 "objects": [{"shape": "plane", "normal": [0, 1, 0], "material": "ground"},
             {"shape": "box", "size": [$3], "position": [$4], "material": "wall"}],
 "droplets": {"file": "drops.csv"}}
JSON
}
