# One asset's GPU rows from lgh-render --repeat (sixteenth session): bash passes.sh LGH_RENDER ASSET
# [SETTINGS_JSON]; N=frames (default 80), EXTRA=--no-frame-overlap for frames drawn one by one.
# usage: fr.sh BIN asset [settings]
G=/usr/share/assimp/models/glTF2; a=$2; s=${3:-'{}'}
echo "{\"scene\":{\"asset\":\"$a\"},\"camera\":{\"type\":\"auto\",\"view_direction\":[1,0.6,1.4]},\"output\":{\"width\":256,\"height\":256,\"format\":\"png\"},\"settings\":$s}" > /tmp/req_$$.json
r=$($1 /tmp/req_$$.json --asset-root $G -o /tmp/fr_$$.png --repeat ${N:-80} $EXTRA --timings /tmp/t_$$.json 2>&1 | grep -o "[0-9.]* frames/s")
python3 -c "
import json; d=json.load(open('/tmp/t_$$.json'))
print('$r', '$(basename $a)', ' '.join(f\"{r['pass'].replace(' ','_')}={r['ms']:.2f}\" for r in d['timings'] if r['clock']!='cpu'))"
