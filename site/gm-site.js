/* The course website's own script (tools/build_site.py copies it into _static/).
   Static copies of ipywidgets sliders are drawn by the widget manager without an accessible
   name: give each slider handle the text of its widget's label (WCAG 4.1.2). */
(function () {
  var here = document.currentScript ? document.currentScript.src : '';
  function nameSliders(root) {
    root.querySelectorAll('.widget-slider, .jupyter-widget-slider').forEach(function (w) {
      var label = w.querySelector('.widget-label, label');
      var text = label ? label.textContent.trim() : '';
      w.querySelectorAll('[role="slider"]').forEach(function (h) {
        if (!h.getAttribute('aria-label') && !h.getAttribute('aria-labelledby')) {
          h.setAttribute('aria-label', text || 'slider');
        }
      });
    });
  }
  /* A pre-rendered sweep (tools/site_sweeps.py) shows the value of its control beside the
     caption: the player marks the frame it shows in its picture's data-frame. */
  function sweeps(root) {
    root.querySelectorAll('.gm-sweep').forEach(function (s) {
      if (s.getAttribute('data-gm-sweep')) return;
      s.setAttribute('data-gm-sweep', '1');
      var values = JSON.parse(s.getAttribute('data-values') || '[]');
      var label = s.getAttribute('data-label') || '';
      var img = s.querySelector('img.gm-anim-frame'), out = s.querySelector('.gm-sweep-value');
      if (!img || !out) return;
      function show() {
        var k = parseInt(img.getAttribute('data-frame') || '0', 10);
        if (values[k] !== undefined) out.textContent = label + ' = ' + values[k];
      }
      new MutationObserver(show).observe(img, {attributes: true, attributeFilter: ['data-frame']});
      show();
    });
  }
  /* A picture shown by an ipywidgets Image widget has no alt text of its own (WCAG 1.1.1): it is
     described by the text its box shows above it (the first HTML widget of the box). */
  function describeImages(root) {
    root.querySelectorAll('img.widget-image:not([alt])').forEach(function (img) {
      var box = img.closest('.widget-box, .jupyter-widgets');
      var html = box ? box.querySelector('.widget-html, .widget-htmlmath') : null;
      var text = html ? html.textContent.replace(/\s+/g, ' ').trim() : '';
      img.setAttribute('alt', text ? text.slice(0, 300) : 'Figure drawn by the exercise');
    });
  }
  /* The search page shows an excerpt of each page found, as text: its formulas arrive as TeX
     (\(L_h g = hg\)), and Sphinx loads MathJax only on pages that have formulas of their own.
     Load the site's MathJax (beside this script in _static/) and typeset each excerpt as it
     arrives (p.context); each is marked data-gm-math="done" once typeset (tools/check_site.py waits for it). */
  var mathjax = null;
  function loadMathJax() {
    if (window.MathJax && window.MathJax.typesetPromise) return Promise.resolve();
    if (!mathjax) {
      mathjax = new Promise(function (ready) {
        window.MathJax = {startup: {typeset: false}};
        var s = document.createElement('script');
        s.src = here.replace(/gm-site\.js(\?.*)?$/, 'mathjax/tex-mml-chtml.js');
        s.onload = function () { window.MathJax.startup.promise.then(ready); };
        document.head.appendChild(s);
      });
    }
    return mathjax;
  }
  /* An excerpt is a window of 240 characters: a formula cut at either end is dropped. */
  function wholeFormulas(p) {
    var t = p.textContent, u = t;
    var open = u.lastIndexOf('\\('), shut = u.lastIndexOf('\\)');
    if (open > shut) u = u.slice(0, open) + '...';
    open = u.indexOf('\\('); shut = u.indexOf('\\)');
    if (shut >= 0 && (open < 0 || shut < open)) u = '...' + u.slice(shut + 2);
    if (u !== t) p.textContent = u;
  }
  function searchMath() {
    var fresh = document.querySelectorAll('#search-results li p.context:not([data-gm-math])');
    if (!fresh.length) return;
    var nodes = Array.prototype.slice.call(fresh);
    nodes.forEach(function (n) { n.setAttribute('data-gm-math', 'pending'); wholeFormulas(n); });
    loadMathJax().then(function () { return window.MathJax.typesetPromise(nodes); })
      .then(function () { nodes.forEach(function (n) { n.setAttribute('data-gm-math', 'done'); }); });
  }
  function start() {
    nameSliders(document);
    sweeps(document);
    describeImages(document);
    new MutationObserver(function () {
      nameSliders(document); sweeps(document); describeImages(document); searchMath();
    }).observe(document.body, {childList: true, subtree: true});
  }
  if (document.readyState === 'loading') { document.addEventListener('DOMContentLoaded', start); } else { start(); }
})();
