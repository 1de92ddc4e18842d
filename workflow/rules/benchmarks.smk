# Chung & Ooi's eight DEM benchmark tests: their own folder, results/chung_ooi/; no chapter file.
CHUNG_OOI = config["chung_ooi"]["tests"]
#: The tests whose reference has the DEM codes' damped Mindlin variant (oblique, COR below 1).
CHUNG_OOI_DAMPED = variant_tests(CHUNG_OOI)


rule chung_ooi:
    """Each test's exact reference (one CSV per test, as `sphereimpact benchmark chung-ooi` writes them; the damped
    Mindlin variant in damped-mindlin/, as `--variant damped-mindlin` writes it), the DEM rules beside the exact contact, their deviations and the verdict `sphereimpact benchmark compare` gives each,
    and each reference's check against its closed form."""
    input:
        definition="src/sphereimpact/study/chung_ooi.yaml",
        curves="data/chung_ooi_paper/curves.csv",
    output:
        tables=expand("results/chung_ooi/test{n}.csv", n=CHUNG_OOI),
        damped=expand("results/chung_ooi/damped-mindlin/test{n}.csv", n=CHUNG_OOI_DAMPED),
        rules="results/chung_ooi/dem_rules.csv",
        deviations=report("results/chung_ooi/deviations.csv", caption="../report/chung_ooi.rst", category="Benchmarks"),
        checks=report("results/chung_ooi/checks.csv", caption="../report/chung_ooi.rst", category="Benchmarks"),
        verdicts=report("results/chung_ooi/verdicts.csv", caption="../report/chung_ooi.rst", category="Benchmarks"),
        published=report("results/chung_ooi/published.csv", caption="../report/chung_ooi.rst", category="Benchmarks"),
    params:
        code=code("workflow/scripts/chung_ooi.py"),
        tests=CHUNG_OOI,
    benchmark:
        "results/benchmarks/benchmarks/chung_ooi.tsv"
    log:
        "logs/benchmarks/chung_ooi.log",
    conda:
        ENV
    script:
        "../scripts/chung_ooi.py"


rule chung_ooi_figures:
    """One figure per test: the exact reference, the DEM rules, and the Kharaz data for test 4."""
    input:
        tables=rules.chung_ooi.output.tables,
        rules=rules.chung_ooi.output.rules,
        data=config["validation"]["data"],
        curves="data/chung_ooi_paper/curves.csv",
    output:
        png=report(
            expand("paper_figures/chung_ooi_test{n}.png", n=CHUNG_OOI), caption="../report/figure.rst", category="Benchmarks"
        ),
    params:
        code=code("workflow/scripts/chung_ooi_figures.py"),
        captions=captions(*(f"chung_ooi_test{n}" for n in CHUNG_OOI)),
    benchmark:
        "results/benchmarks/benchmarks/chung_ooi_figures.tsv"
    log:
        "logs/benchmarks/chung_ooi_figures.log",
    conda:
        ENV
    script:
        "../scripts/chung_ooi_figures.py"


rule chung_ooi_readme:
    """The README's block of the benchmark tests: each reference's check and the DEM rules' largest deviation."""
    input:
        checks=rules.chung_ooi.output.checks,
        deviations=rules.chung_ooi.output.deviations,
        published=rules.chung_ooi.output.published,
    output:
        md="results/readme/chung_ooi.md",
    params:
        code=code("workflow/scripts/chung_ooi_readme.py"),
    benchmark:
        "results/benchmarks/benchmarks/chung_ooi_readme.tsv"
    log:
        "logs/benchmarks/chung_ooi_readme.log",
    conda:
        ENV
    script:
        "../scripts/chung_ooi_readme.py"


rule dem_departure:
    """What each DEM tangential rule costs: its largest departure from the exact contact on Chung & Ooi's oblique
    tests (their deviations) and on the Kharaz ball over the validation's incidences."""
    input:
        deviations=rules.chung_ooi.output.deviations,
    output:
        kharaz="results/chung_ooi/departure_kharaz.csv",
        departure=report("results/chung_ooi/departure.csv", caption="../report/chung_ooi.rst", category="Benchmarks"),
    params:
        code=code("workflow/scripts/dem_departure.py"),
        config=params_for("dem_departure"),
    benchmark:
        "results/benchmarks/benchmarks/dem_departure.tsv"
    log:
        "logs/benchmarks/dem_departure.log",
    conda:
        ENV
    script:
        "../scripts/dem_departure.py"


rule dem_departure_report:
    """The departure figure and the docs' block."""
    input:
        departure=rules.dem_departure.output.departure,
    output:
        png=report("paper_figures/dem_departure.png", caption="../report/figure.rst", category="Benchmarks"),
        md="results/readme/dem_departure.md",
    params:
        code=code("workflow/scripts/dem_departure_report.py"),
        captions=captions("dem_departure"),
    benchmark:
        "results/benchmarks/benchmarks/dem_departure_report.tsv"
    log:
        "logs/benchmarks/dem_departure_report.log",
    conda:
        ENV
    script:
        "../scripts/dem_departure_report.py"
