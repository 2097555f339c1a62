"""Trial helper (docs/validation.md 7.49): plot the water particles that the trial build of
docs/trials/energy_budget.diff dumps with SWELL_DUMP=t1,t2,... SWELL_DUMP_DIR=DIR, near the
Lobovsky tank's far wall. Usage: /usr/bin/python3 docs/trials/runup_plot.py DIR 0.600 0.700 ...
(a multiple of three times, each as its file is named); writes DIR/runup.png. Fixed particles
black, water coloured by speed (0-3.5 m/s), free-surface particles red, the gauges H2-H4 grey."""
import csv,sys,matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
ts=sys.argv[2:]
fig,axs=plt.subplots(len(ts)//3,3,figsize=(15,3.6*len(ts)//3))
for ax,t in zip(axs.flat,ts):
    rows=list(csv.DictReader(open(f'{sys.argv[1]}/{t}.csv')))
    w=[r for r in rows if r['kind']=='0']
    f=[r for r in rows if r['kind']!='0']
    ax.scatter([float(r['x']) for r in f],[float(r['y']) for r in f],s=1,c='k')
    sc=ax.scatter([float(r['x']) for r in w],[float(r['y']) for r in w],s=2,c=[(float(r['vx'])**2+float(r['vy'])**2)**.5 for r in w],cmap='viridis',vmin=0,vmax=3.5)
    s=[r for r in w if r['surface']=='1']
    ax.scatter([float(r['x']) for r in s],[float(r['y']) for r in s],s=2,c='r')
    for gx in (0.865,1.114,1.3625): ax.axvline(gx,color='gray',lw=0.5)
    ax.set_xlim(0.8,1.65); ax.set_ylim(0,0.7); ax.set_aspect('equal'); ax.set_title(f't = {t} s')
plt.tight_layout(); plt.savefig(sys.argv[1]+'/runup.png',dpi=60)
