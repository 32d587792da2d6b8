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
  function start() {
    nameSliders(document);
    new MutationObserver(function () { nameSliders(document); })
      .observe(document.body, {childList: true, subtree: true});
  }
  if (document.readyState === 'loading') { document.addEventListener('DOMContentLoaded', start); } else { start(); }
})();
