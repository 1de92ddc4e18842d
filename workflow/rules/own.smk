# A study of one's own ball (config key `study` other than chapter4): everything under results/studies/<name>/.
# The chapter's rules are not asked for by such a study (see the Snakefile's rule all), so it never writes their
# files, and the benchmarks and numerical studies are not rerun for it.


OWN = f"results/studies/{config['study']}"
BOUNCES = list(config["bounces"])
#: The fit's files when the study fits its ball to measured bounces (config section `fit`).
FIT = [f"{OWN}/fit/{name}" for name in FIT_FILES] if config.get("fit") else []
#: The plan's files when the study plans its measurements (config section `plan`).
PLAN = [f"{OWN}/plan/{name}" for name in PLAN_FILES] if config.get("plan") else []


rule own_fit:
    """The ball fitted to the measured bounces of the config's `fit` section (the study then uses it)."""
    input:
        data=config["fit"]["data"] if config.get("fit") else [],
        ball_file=[config["ball_file"]] if config.get("ball_file") else [],
    output:
        ball=f"{OWN}/fit/ball.json",
        summary=f"{OWN}/fit/fit.json",
        residuals=f"{OWN}/fit/residuals.csv",
        png=report(f"{OWN}/fit/fit.png", caption="../report/own.rst", category="Own study"),
    params:
        code=code("workflow/scripts/own_fit.py"),
        config=params_for("own_fit"),
    benchmark:
        f"{OWN}/benchmarks/fit.tsv",
    log:
        f"logs/studies/{config['study']}/fit.log",
    conda:
        ENV
    script:
        "../scripts/own_fit.py"


rule own_plan:
    """Which bounces to measure: the config's `plan` section for the study's ball (sphereimpact plan)."""
    input:
        candidates=config["plan"]["candidates"] if config.get("plan") else [],
        ball=f"{OWN}/ball.json",
    output:
        table=f"{OWN}/plan/plan.csv",
        summary=f"{OWN}/plan/plan.json",
        candidates=f"{OWN}/plan/candidates.csv",
        png=report(f"{OWN}/plan/plan.png", caption="../report/own.rst", category="Own study"),
    params:
        code=code("workflow/scripts/own_plan.py"),
        config=params_for("own_plan"),
    benchmark:
        f"{OWN}/benchmarks/plan.tsv",
    log:
        f"logs/studies/{config['study']}/plan.log",
    conda:
        ENV
    script:
        "../scripts/own_plan.py"


rule own_ball:
    """The study's ball: its contact law's damping (and stiffness) fitted to the measured COR (and contact time),
    or read from the configured ball file."""
    input:
        ball_file=[config["ball_file"]] if config.get("ball_file") else [],
        fitted=FIT[:1],
    output:
        ball=f"{OWN}/ball.json",
    params:
        code=code("workflow/scripts/own_ball.py"),
        config=params_for("own_ball"),
    benchmark:
        f"{OWN}/benchmarks/ball.tsv",
    log:
        f"logs/studies/{config['study']}/ball.log",
    conda:
        ENV
    script:
        "../scripts/own_ball.py"


rule own_bounces:
    """Each configured bounce: every scalar output, and its time history (units in the CSV header)."""
    input:
        ball=f"{OWN}/ball.json",
    output:
        outcomes=report(f"{OWN}/outcomes.csv", caption="../report/own.rst", category="Own study"),
        histories=expand(f"{OWN}/histories/{{bounce}}.csv", bounce=BOUNCES),
    params:
        code=code("workflow/scripts/own_bounces.py"),
        config=params_for("own_bounces"),
    benchmark:
        f"{OWN}/benchmarks/bounces.tsv",
    log:
        f"logs/studies/{config['study']}/bounces.log",
    conda:
        ENV
    script:
        "../scripts/own_bounces.py"


rule own_speed:
    """Normal impacts across the configured speeds: COR, contact time, peak force, maximum compression."""
    input:
        ball=f"{OWN}/ball.json",
    output:
        csv=f"{OWN}/speed.csv",
    params:
        code=code("workflow/scripts/own_sweep.py"),
        config=params_for("own_speed"),
    benchmark:
        f"{OWN}/benchmarks/speed.tsv",
    log:
        f"logs/studies/{config['study']}/speed.log",
    conda:
        ENV
    script:
        "../scripts/own_sweep.py"


rule own_maps:
    """Angle to the surface x speed at the configured spin: rebound spin, velocities and angles."""
    input:
        ball=f"{OWN}/ball.json",
    output:
        csv=f"{OWN}/maps.csv",
    params:
        code=code("workflow/scripts/own_sweep.py"),
        config=params_for("own_maps"),
    benchmark:
        f"{OWN}/benchmarks/maps.tsv",
    log:
        f"logs/studies/{config['study']}/maps.log",
    conda:
        ENV
    script:
        "../scripts/own_sweep.py"


rule own_bounce_figure:
    """One bounce's history: displacement, velocities, spin, force against compression."""
    input:
        history=f"{OWN}/histories/{{bounce}}.csv",
    output:
        png=report(f"{OWN}/figures/{{bounce}}.png", caption="../report/own.rst", category="Own study"),
    params:
        code=code("workflow/scripts/own_bounce_figure.py"),
        config=params_for("own_bounce_figure"),
    benchmark:
        f"{OWN}/benchmarks/figure_{{bounce}}.tsv",
    log:
        f"logs/studies/{config['study']}/figure_{{bounce}}.log",
    conda:
        ENV
    script:
        "../scripts/own_bounce_figure.py"


rule own_figures:
    """The speed curve's figure and the two maps."""
    input:
        speed=f"{OWN}/speed.csv",
        maps=f"{OWN}/maps.csv",
        ball=f"{OWN}/ball.json",
    output:
        speed=f"{OWN}/figures/speed.png",
        spin_map=f"{OWN}/figures/spin_map.png",
        rebound_map=f"{OWN}/figures/rebound_map.png",
    params:
        code=code("workflow/scripts/own_figures.py"),
        config=params_for("own_figures"),
    benchmark:
        f"{OWN}/benchmarks/figures.tsv",
    log:
        f"logs/studies/{config['study']}/figures.log",
    conda:
        ENV
    script:
        "../scripts/own_figures.py"


rule own_page:
    """One page (Markdown and HTML) with the ball's parameters, the bounces, the curves and maps."""
    input:
        ball=f"{OWN}/ball.json",
        outcomes=f"{OWN}/outcomes.csv",
        speed=f"{OWN}/speed.csv",
        maps=f"{OWN}/maps.csv",
        figures=[*expand(f"{OWN}/figures/{{bounce}}.png", bounce=BOUNCES),
                 *(f"{OWN}/figures/{name}.png" for name in ("speed", "spin_map", "rebound_map"))],
        benchmarks=[*(f"{OWN}/benchmarks/{name}.tsv" for name in ("ball", "bounces", "speed", "maps", "figures")),
                    *expand(f"{OWN}/benchmarks/figure_{{bounce}}.tsv", bounce=BOUNCES),
                    *([f"{OWN}/benchmarks/fit.tsv"] if FIT else []),
                    *([f"{OWN}/benchmarks/plan.tsv"] if PLAN else [])],
        fit=FIT,
        plan=PLAN,
    output:
        md=f"{OWN}/index.md",
        html=report(f"{OWN}/index.html", caption="../report/own.rst", category="Own study"),
    params:
        code=code("workflow/scripts/own_page.py"),
        config=params_for("own_page"),
    log:
        f"logs/studies/{config['study']}/page.log",
    conda:
        ENV
    script:
        "../scripts/own_page.py"
