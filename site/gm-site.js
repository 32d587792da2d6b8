/* The course website's own script (tools/build_site.py copies it into _static/).
   Static copies of ipywidgets sliders are drawn by the widget manager without an accessible
   name: give each slider handle the text of its widget's label (WCAG 4.1.2). */
(function () {
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
  function start() {
    nameSliders(document);
    sweeps(document);
    describeImages(document);
    new MutationObserver(function () { nameSliders(document); sweeps(document); describeImages(document); })
      .observe(document.body, {childList: true, subtree: true});
  }
  if (document.readyState === 'loading') { document.addEventListener('DOMContentLoaded', start); } else { start(); }
})();
