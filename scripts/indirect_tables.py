# Regenerates the indirect-lighting tables (docs/measured/indirect.md) from the run
# folders of the sweeps listed there: scripts/indirect_tables.py headline|N|s|R|Rl [RUNS_DIR]
import json,sys
RUNS = sys.argv[2] if len(sys.argv) > 2 else '/tmp/meas'
def load(p): return json.load(open(p.replace('/tmp/meas', RUNS)))['records']
def f(v,fmt): return fmt%v if isinstance(v,(int,float)) else str(v)
def row(r, keys):
    return '| '+' | '.join(keys(r))+' |'
def common(r):
    ms=lambda k: '%.1f'%r.get(k+'_ms_median',0)
    mib=lambda k: '%.2f'%(r[k]/2**20)
    return [ms('build'), ms('light_gbuffer'), ms('photon_tracing'), ms('splatting'), ms('direct'), ms('frame'),
            mib('m_lists_allocated'), mib('m_photons_used'),
            '{:,}'.format(r['photons_stored']), '%.2e'%r['mse'], '%.1f'%r['mse_over_noise'], '%.3f'%r['mssim'], '%.2e'%r['multi_mse'], '%.3f'%r['multi_mssim']]
hdr='build ms | light G-buffer ms | tracing ms | splatting ms | direct ms | frame ms | M_lists MiB | M_photons MiB | photons stored | MSE single | ×noise | MSSIM single | MSE multi | MSSIM multi'
mode=sys.argv[1]
if mode=='headline':
    print('| scene | structure | status | '+hdr+' |'); print('|'+' --- |'*3+' ---: |'*14)
    for r in load('/tmp/meas/headline/records.json'):
        print('| %s | %s | %s | '%(r['scene'],r['structure'],r['status'])+' | '.join(common(r))+' |')
else:
    axis={'N':('n_views','N'),'s':('splat_scale','s = a'),'R':('r_ldm','R_LDM'),'Rl':('r_light','R_light')}[mode]
    print('| scene | %s | '%axis[1]+hdr+' |'); print('|'+' --- |'*2+' ---: |'*14)
    for scene in ['cornell','atrium']:
        for r in load('/tmp/meas/%s-%s/records.json'%(scene,mode)):
            print('| %s | %s | '%(scene, f(r[axis[0]],'%g'))+' | '.join(common(r))+' |')
